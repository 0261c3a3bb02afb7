// STL reader, ASCII and binary.
//
// Binary STL: 80-byte header, uint32 triangle count n, then n records of
// 50 bytes (normal, three vertices as float32 little-endian, uint16 attribute).
// A file is taken as binary when its size is exactly 84 + 50 n; many binary
// files start with "solid" in the header, so the keyword alone is not trusted.
// A file that does not start with "solid" and is shorter than 84 + 50 n is a
// truncated binary STL. Stored normals are ignored: orientation comes from the
// vertex order and is checked by validation.

#include "io/mesh/mesh_reader.hpp"
#include "io/mesh/mesh_text.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace grains::mesh {
namespace {

float read_f32(const unsigned char* p) {
  uint32_t u = uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

TriangleMesh parse_binary(const std::string& bytes, const std::string& path, uint64_t n) {
  TriangleMesh mesh;
  mesh.source = path;
  detail::VertexWelder weld(mesh);
  const auto* base = reinterpret_cast<const unsigned char*>(bytes.data()) + 84;
  for (uint64_t t = 0; t < n; ++t) {
    const unsigned char* rec = base + 50 * t;
    std::array<int, 3> f{};
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d p;
      for (int d = 0; d < 3; ++d) p[d] = read_f32(rec + 12 + 12 * k + 4 * d);
      if (!p.allFinite()) {
        throw MeshError(MeshErrorKind::non_finite,
                        path + ": binary STL triangle " + std::to_string(t) + " vertex " +
                            std::to_string(k) + " has a non-finite coordinate " +
                            detail::vec_to_string(p) + "; every coordinate must be finite");
      }
      f[k] = weld.index_of(p);
    }
    mesh.faces.push_back(f);
  }
  return mesh;
}

void expect(detail::Tokenizer& tok, std::string_view word, const std::string& path) {
  const std::string_view t = tok.next();
  if (t != word) {
    throw MeshError(MeshErrorKind::parse,
                    path + ":" + std::to_string(tok.line()) + ": expected '" + std::string(word) +
                        "' in ASCII STL but found '" + std::string(t.empty() ? "end of file" : t) +
                        "'");
  }
}

TriangleMesh parse_ascii(const std::string& bytes, const std::string& path) {
  TriangleMesh mesh;
  mesh.source = path;
  detail::VertexWelder weld(mesh);
  detail::Tokenizer tok(bytes, false);
  expect(tok, "solid", path);
  // The solid name runs to the end of the line; skip tokens until 'facet' or 'endsolid'.
  std::string_view t = tok.next();
  const int first_line = tok.line();
  while (!t.empty() && t != "facet" && t != "endsolid" && tok.line() == first_line) t = tok.next();
  while (t == "facet") {
    expect(tok, "normal", path);
    for (int d = 0; d < 3; ++d) detail::parse_coordinate(tok.next(), path, tok.line());
    expect(tok, "outer", path);
    expect(tok, "loop", path);
    std::array<int, 3> f{};
    for (int k = 0; k < 3; ++k) {
      expect(tok, "vertex", path);
      Eigen::Vector3d p;
      for (int d = 0; d < 3; ++d) p[d] = detail::parse_coordinate(tok.next(), path, tok.line());
      f[k] = weld.index_of(p);
    }
    t = tok.next();
    if (t == "vertex") {
      throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(tok.line()) +
                                                ": facet with more than three vertices; STL facets are triangles");
    }
    if (t != "endloop") {
      throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(tok.line()) +
                                                ": expected 'endloop' but found '" + std::string(t) + "'");
    }
    expect(tok, "endfacet", path);
    mesh.faces.push_back(f);
    t = tok.next();
  }
  if (t != "endsolid") {
    throw MeshError(MeshErrorKind::parse,
                    path + ":" + std::to_string(tok.line()) + ": expected 'facet' or 'endsolid' but found '" +
                        std::string(t.empty() ? "end of file" : t) + "' (ASCII STL ends with 'endsolid')");
  }
  return mesh;
}

}  // namespace

TriangleMesh read_stl(const std::string& path) {
  const std::string bytes = detail::read_file_bytes(path);
  const bool starts_solid = bytes.size() >= 5 && bytes.compare(0, 5, "solid") == 0;
  if (bytes.size() >= 84) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data()) + 80;
    const uint64_t n = uint64_t(p[0]) | (uint64_t(p[1]) << 8) | (uint64_t(p[2]) << 16) | (uint64_t(p[3]) << 24);
    const uint64_t expected = 84 + 50 * n;
    if (bytes.size() == expected) {
      if (n == 0) {
        throw MeshError(MeshErrorKind::empty, path + ": binary STL with 0 triangles; a mesh needs faces");
      }
      return parse_binary(bytes, path, n);
    }
    if (!starts_solid) {
      if (bytes.size() < expected) {
        throw MeshError(MeshErrorKind::truncated,
                        path + ": truncated binary STL: header promises " + std::to_string(n) +
                            " triangles (" + std::to_string(expected) + " bytes) but the file has " +
                            std::to_string(bytes.size()) + " bytes (" +
                            std::to_string((bytes.size() - 84) / 50) + " complete triangles)");
      }
      throw MeshError(MeshErrorKind::parse,
                      path + ": binary STL has " + std::to_string(bytes.size() - expected) +
                          " bytes after the " + std::to_string(n) +
                          " triangles its header promises (expected exactly 84 + 50 n bytes)");
    }
  } else if (!starts_solid) {
    throw MeshError(MeshErrorKind::truncated,
                    path + ": truncated binary STL: " + std::to_string(bytes.size()) +
                        " bytes, less than the 84-byte header (an ASCII STL starts with 'solid')");
  }
  TriangleMesh mesh = parse_ascii(bytes, path);
  if (mesh.faces.empty()) {
    throw MeshError(MeshErrorKind::empty, path + ": ASCII STL has no facets; a mesh needs faces");
  }
  return mesh;
}

}  // namespace grains::mesh
