#pragma once
// Small helpers shared by the mesh readers: slurping a file, a line-aware
// tokenizer for the text formats, and vertex welding for STL.

#include "io/mesh/mesh_error.hpp"
#include "contact/mesh/triangle_mesh.hpp"

#include <array>
#include <map>
#include <string>
#include <string_view>

namespace grains::mesh::detail {

// Whole file as bytes; throws cannot_open / empty.
std::string read_file_bytes(const std::string& path);

// Tokens separated by white space, with the line number of each token.
// '#' starts a comment to the end of the line when `hash_comments` is set.
class Tokenizer {
public:
  Tokenizer(std::string_view text, bool hash_comments) : text_(text), hash_(hash_comments) {}
  // Next token on any line; empty view at end of input.
  std::string_view next();
  int line() const { return token_line_; }
  bool at_end();

private:
  void skip_space();
  std::string_view text_;
  bool hash_;
  size_t pos_ = 0;
  int line_ = 1;
  int token_line_ = 1;
};

// Parse a double; throws MeshError(parse) naming path:line on failure and
// MeshError(non_finite) if it parses to NaN or infinity.
double parse_coordinate(std::string_view token, const std::string& path, int line);
long parse_integer(std::string_view token, const std::string& path, int line, const char* what);

// Welds vertices that have bit-identical coordinates.
class VertexWelder {
public:
  explicit VertexWelder(TriangleMesh& mesh) : mesh_(mesh) {}
  int index_of(const Eigen::Vector3d& p);

private:
  TriangleMesh& mesh_;
  std::map<std::array<double, 3>, int> index_;
};

std::string vec_to_string(const Eigen::Vector3d& p);

}  // namespace grains::mesh::detail
