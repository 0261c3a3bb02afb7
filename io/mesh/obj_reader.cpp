// Wavefront OBJ reader: only geometry is read (`v` and `f`); texture
// coordinates, normals, groups and materials are skipped. Polygons are
// fan-triangulated from their first vertex.

#include "io/mesh/mesh_reader.hpp"
#include "io/mesh/mesh_text.hpp"

#include <sstream>

namespace grains::mesh {

TriangleMesh read_obj(const std::string& path) {
  const std::string bytes = detail::read_file_bytes(path);
  TriangleMesh mesh;
  mesh.source = path;
  std::vector<std::pair<std::vector<long>, int>> polygons;  // raw indices + line
  std::istringstream in(bytes);
  std::string line_text;
  int line = 0;
  while (std::getline(in, line_text)) {
    ++line;
    if (const auto hash = line_text.find('#'); hash != std::string::npos) line_text.resize(hash);
    detail::Tokenizer tok(line_text, false);
    const std::string_view key = tok.next();
    if (key == "v") {
      Eigen::Vector3d p;
      for (int d = 0; d < 3; ++d) p[d] = detail::parse_coordinate(tok.next(), path, line);
      mesh.vertices.push_back(p);
    } else if (key == "f") {
      std::vector<long> idx;
      for (std::string_view t = tok.next(); !t.empty(); t = tok.next()) {
        idx.push_back(detail::parse_integer(t.substr(0, t.find('/')), path, line, "a vertex index"));
      }
      if (idx.size() < 3) {
        throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(line) +
                                                  ": face with fewer than 3 vertices");
      }
      polygons.emplace_back(std::move(idx), line);
    }
  }
  if (polygons.empty()) {
    throw MeshError(MeshErrorKind::empty, path + ": OBJ file has no faces ('f' lines); a mesh needs faces");
  }
  const long nv = static_cast<long>(mesh.vertices.size());
  for (const auto& [idx, fline] : polygons) {
    std::vector<int> resolved;
    for (long i : idx) {
      const long r = i > 0 ? i - 1 : nv + i;  // 1-based, negative counts back from the end
      if (i == 0 || r < 0 || r >= nv) {
        throw MeshError(MeshErrorKind::parse,
                        path + ":" + std::to_string(fline) + ": vertex index " + std::to_string(i) +
                            " out of range; valid are 1.." + std::to_string(nv) + " or -1..-" +
                            std::to_string(nv));
      }
      resolved.push_back(static_cast<int>(r));
    }
    for (size_t k = 1; k + 1 < resolved.size(); ++k) {
      mesh.faces.push_back({resolved[0], resolved[k], resolved[k + 1]});
    }
  }
  return mesh;
}

}  // namespace grains::mesh
