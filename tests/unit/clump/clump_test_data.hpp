#pragma once
#include "io/mesh/mesh_reader.hpp"

#include <string>

inline std::string mesh_path(const std::string& name) {
  return std::string(GRAINS_SOURCE_DIR) + "/tests/data/meshes/" + name;
}
inline grains::mesh::TriangleMesh test_mesh(const std::string& name) { return grains::mesh::load_mesh(mesh_path(name)); }
