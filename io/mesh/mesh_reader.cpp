#include "io/mesh/mesh_reader.hpp"

#include "io/mesh/mesh_error.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace grains::mesh {

TriangleMesh read_mesh(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".stl") return read_stl(path);
  if (ext == ".obj") return read_obj(path);
  if (ext == ".off") return read_off(path);
  throw MeshError(MeshErrorKind::unknown_format,
                  path + ": unknown mesh format '" + ext + "'; valid extensions are .stl, .obj and .off");
}

TriangleMesh load_mesh(const std::string& path, const ValidationOptions& options) {
  TriangleMesh mesh = read_mesh(path);
  validate_mesh(mesh, options);
  return mesh;
}

}  // namespace grains::mesh
