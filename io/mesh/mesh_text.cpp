#include "io/mesh/mesh_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace grains::mesh::detail {

std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw MeshError(MeshErrorKind::cannot_open,
                    path + ": cannot open mesh file (check the path and permissions)");
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  std::string bytes = ss.str();
  if (bytes.empty()) {
    throw MeshError(MeshErrorKind::empty,
                    path + ": the mesh file is empty (0 bytes); expected an STL, OBJ or OFF mesh");
  }
  return bytes;
}

void Tokenizer::skip_space() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
    } else if (hash_ && c == '#') {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
}

bool Tokenizer::at_end() {
  skip_space();
  return pos_ >= text_.size();
}

std::string_view Tokenizer::next() {
  skip_space();
  const size_t start = pos_;
  token_line_ = line_;
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') break;
    if (hash_ && c == '#') break;
    ++pos_;
  }
  return text_.substr(start, pos_ - start);
}

double parse_coordinate(std::string_view token, const std::string& path, int line) {
  if (token.empty()) {
    throw MeshError(MeshErrorKind::parse,
                    path + ":" + std::to_string(line) + ": expected a coordinate but the file ended");
  }
  // strtod accepts "nan" and "inf" so that they are reported as non-finite,
  // not as a syntax error.
  const std::string s(token);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) {
    throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(line) + ": '" + s +
                                              "' is not a number (expected a coordinate)");
  }
  if (!std::isfinite(v)) {
    throw MeshError(MeshErrorKind::non_finite,
                    path + ":" + std::to_string(line) + ": non-finite coordinate '" + s +
                        "'; every vertex coordinate must be a finite number");
  }
  return v;
}

long parse_integer(std::string_view token, const std::string& path, int line, const char* what) {
  long v = 0;
  const auto [p, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  if (token.empty() || ec != std::errc() || p != token.data() + token.size()) {
    throw MeshError(MeshErrorKind::parse, path + ":" + std::to_string(line) + ": '" +
                                              std::string(token) + "' is not an integer (expected " +
                                              what + ")");
  }
  return v;
}

int VertexWelder::index_of(const Eigen::Vector3d& p) {
  const std::array<double, 3> key{p.x() + 0.0, p.y() + 0.0, p.z() + 0.0};  // -0 welds with +0
  auto [it, inserted] = index_.try_emplace(key, static_cast<int>(mesh_.vertices.size()));
  if (inserted) mesh_.vertices.push_back(p);
  return it->second;
}

std::string vec_to_string(const Eigen::Vector3d& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return buf;
}

}  // namespace grains::mesh::detail
