#pragma once
// Clump shapes for particle sets (`shape: {type: clump, ...}`): read from a
// clump file (contact/clump/clump_yaml.hpp), or decomposed from a mesh at
// load time and cached.
//
// Cache: a mesh decomposition is written as a clump file named by a 64-bit
// FNV-1a hash of the mesh file's bytes, the grid, mu and the format version
// (clump_<hash>.yaml), in $GRAINS_CACHE_DIR, else $XDG_CACHE_HOME/grains/clumps,
// else ~/.cache/grains/clumps. Any change of the mesh or the parameters gives
// another name; a cache that cannot be written only costs the decomposition
// at the next run. Within one process shapes are also kept in memory.
#include <filesystem>
#include <memory>
#include <string>

#include "contact/clump/clump_template.hpp"
#include "sim/scene/scene_config.hpp"

namespace grains::io {

/// The template scaled to a bounding radius of 1 about its centre of mass,
/// mass properties per unit density.
sim::ClumpShape normalised_clump_shape(const clump::ClumpTemplate& t, const std::string& source);

/// From a clump file. Throws std::runtime_error with the reason.
std::shared_ptr<const sim::ClumpShape> clump_shape_from_file(const std::string& path);

/// From a mesh, decomposed with grid N and protrusion mu (cached). Throws
/// std::runtime_error (mesh errors included) with the reason.
std::shared_ptr<const sim::ClumpShape> clump_shape_from_mesh(const std::string& path, int grid, double mu);

/// The cache folder in use and the cache file of a mesh decomposition.
std::filesystem::path clump_cache_dir();
std::filesystem::path clump_cache_file(const std::string& mesh_path, int grid, double mu);

}  // namespace grains::io
