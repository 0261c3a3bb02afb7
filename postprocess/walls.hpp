#pragma once
// Walls read back from a frame's walls_NNNNNN.vtp and the particle-wall
// contacts of a frame, so that coordination numbers of particles resting on
// walls count those contacts too. io/output/vtk_output.cpp writes each wall's
// record (its kind's record(), sim/walls/wall_kind.hpp) as a field-data array
// `wall_<index>_<kind>`; the walls are rebuilt from those with the simulation's
// own wall kinds, so `grains analyze` uses the contact geometry of the run.
#include <filesystem>
#include <vector>

#include "postprocess/frame.hpp"
#include "sim/walls/walls.hpp"

namespace grains::postprocess {

using WallSet = sim::Walls;

/// Throws std::runtime_error when the file cannot be read or names a wall
/// kind this build does not know.
WallSet read_walls(const std::filesystem::path& vtp);

/// Number of walls each particle touches (overlap > -gap): spheres with
/// their radius + gap, ellipsoids with their semi-axes + gap, through each
/// wall kind's contact geometry.
std::vector<int> wall_contacts(const Frame& f, const WallSet& w, double gap = 0);

}  // namespace grains::postprocess
