// OFF reader: `OFF` keyword, then `nv nf ne`, nv vertex lines and nf polygon
// lines `k i1 ... ik` (0-based; trailing colour values are ignored).
// '#' comments are allowed. Polygons are fan-triangulated.

#include "io/mesh/mesh_reader.hpp"
#include "io/mesh/mesh_text.hpp"

#include <sstream>

namespace grains::mesh {

TriangleMesh read_off(const std::string& path) {
  const std::string bytes = detail::read_file_bytes(path);
  TriangleMesh mesh;
  mesh.source = path;
  // Line-based so that optional per-face colours are skipped reliably.
  std::vector<std::pair<std::string, int>> lines;
  {
    std::istringstream in(bytes);
    std::string s;
    int n = 0;
    while (std::getline(in, s)) {
      ++n;
      if (const auto hash = s.find('#'); hash != std::string::npos) s.resize(hash);
      if (s.find_first_not_of(" \t\r") != std::string::npos) lines.emplace_back(s, n);
    }
  }
  if (lines.empty()) {
    throw MeshError(MeshErrorKind::empty, path + ": OFF file has no content; expected 'OFF' and counts");
  }
  size_t li = 0;
  std::string header = lines[0].first;
  header.erase(0, header.find_first_not_of(" \t"));
  if (header.compare(0, 3, "OFF") != 0) {
    throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(lines[0].second) +
                                              ": expected the keyword 'OFF' on the first line");
  }
  // Counts may follow OFF on the same line.
  std::string counts = header.substr(3);
  if (counts.find_first_not_of(" \t\r") == std::string::npos) {
    if (++li >= lines.size()) {
      throw MeshError(MeshErrorKind::empty, path + ": OFF file ends after the header; expected 'nv nf ne'");
    }
    counts = lines[li].first;
  }
  const int counts_line = lines[li].second;
  detail::Tokenizer ct(counts, false);
  const long nv = detail::parse_integer(ct.next(), path, counts_line, "the vertex count");
  const long nf = detail::parse_integer(ct.next(), path, counts_line, "the face count");
  if (nv < 0 || nf < 0) {
    throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(counts_line) + ": negative counts");
  }
  if (nv == 0 || nf == 0) {
    throw MeshError(MeshErrorKind::empty, path + ":" + std::to_string(counts_line) + ": OFF declares " +
                                              std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                              " faces; a mesh needs both");
  }
  ++li;
  auto need = [&](const char* what, long index) {
    if (li >= lines.size()) {
      throw MeshError(MeshErrorKind::parse, path + ": file ends before " + what + " " + std::to_string(index) +
                                                " (declared " + std::to_string(nv) + " vertices, " +
                                                std::to_string(nf) + " faces)");
    }
  };
  // The declared counts must fit in the file before anything is allocated
  // for them (a corrupt count must not ask for terabytes; found by fuzzing).
  const auto remaining = static_cast<long>(lines.size() - li);
  if (nv > remaining || nf > remaining - nv) {
    throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(counts_line) + ": OFF declares " +
                                              std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                              " faces, but only " + std::to_string(remaining) +
                                              " lines follow (truncated file or wrong counts)");
  }
  mesh.vertices.reserve(static_cast<std::size_t>(nv));
  for (long i = 0; i < nv; ++i, ++li) {
    need("vertex", i);
    detail::Tokenizer t(lines[li].first, false);
    Eigen::Vector3d p;
    for (int d = 0; d < 3; ++d) p[d] = detail::parse_coordinate(t.next(), path, lines[li].second);
    mesh.vertices.push_back(p);
  }
  for (long f = 0; f < nf; ++f, ++li) {
    need("face", f);
    const int line = lines[li].second;
    detail::Tokenizer t(lines[li].first, false);
    const long k = detail::parse_integer(t.next(), path, line, "the polygon size");
    if (k < 3) {
      throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(line) + ": polygon with " +
                                                std::to_string(k) + " vertices; at least 3 are needed");
    }
    std::vector<int> idx;
    for (long j = 0; j < k; ++j) {
      const long i = detail::parse_integer(t.next(), path, line, "a vertex index");
      if (i < 0 || i >= nv) {
        throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(line) + ": vertex index " +
                                                  std::to_string(i) + " out of range 0.." + std::to_string(nv - 1));
      }
      idx.push_back(static_cast<int>(i));
    }
    for (size_t j = 1; j + 1 < idx.size(); ++j) mesh.faces.push_back({idx[0], idx[j], idx[j + 1]});
  }
  return mesh;
}

}  // namespace grains::mesh
