#pragma once
// Walls read back from a frame's walls_NNNNNN.vtp (io/output/vtk_output.cpp
// writes each plane as one quad, each cylinder as a ring of quads between
// its bottom and top circles and each finite plane as a ring of quads between
// its hole and its outer rim, with cell arrays `wall` numbering the walls and
// `wall_type` telling the last two apart; files without `wall_type` have no
// finite planes),
// and the particle-wall contacts of a frame, so that coordination numbers of
// particles resting on walls count those contacts too.
#include <filesystem>
#include <vector>

#include "postprocess/frame.hpp"

namespace grains::postprocess {

struct PlaneWall {
  Vec3 point{0, 0, 0}, normal{0, 0, 1};  // unit normal; the side does not matter here
};

struct CylinderWall {
  Vec3 base{0, 0, 0}, axis{0, 0, 1};  // unit axis; base is the bottom circle's centre
  double radius = 0, length = 0;
};

/// A finite plane: an annulus of radii r_in (hole) and r_out about centre.
struct AnnulusWall {
  Vec3 centre{0, 0, 0}, normal{0, 0, 1};
  double r_in = 0, r_out = 0;
};

struct WallSet {
  std::vector<PlaneWall> planes;
  std::vector<CylinderWall> cylinders;
  std::vector<AnnulusWall> annuli;
  bool empty() const { return planes.empty() && cylinders.empty() && annuli.empty(); }
};

/// Throws std::runtime_error when the file cannot be read.
WallSet read_walls(const std::filesystem::path& vtp);

/// Number of walls each particle touches (overlap > -gap). Spheres use their
/// radius; ellipsoids their support distance along the wall normal.
std::vector<int> wall_contacts(const Frame& f, const WallSet& w, double gap = 0);

}  // namespace grains::postprocess
