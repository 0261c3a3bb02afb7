#pragma once
#include "io/mesh/mesh_reader.hpp"

#include <string>

inline std::string mesh_path(const std::string& name) {
  return std::string(GRAINS_SOURCE_DIR) + "/tests/data/meshes/" + name;
}
inline grains::mesh::TriangleMesh test_mesh(const std::string& name) { return grains::mesh::load_mesh(mesh_path(name)); }

#include "contact/clump/mesh_distance.hpp"

// Reference signed distance for tests: exact unsigned distance, sign from the
// generalized winding number (slow, robust).
inline double reference_signed_distance(const grains::clump::MeshDistance& d, const Eigen::Vector3d& p) {
  const double u = d.unsigned_distance(p);
  return d.winding_number(p) > 0.5 ? -u : u;
}
