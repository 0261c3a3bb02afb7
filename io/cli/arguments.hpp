#pragma once
// Parsing of command-line option values shared by the commands
// (analyze, render, repose): whole-string numbers and comma lists.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace grains::io::cli_args {

/// A finite number spanning the whole string.
inline bool parse_number(const std::string& s, double& v) {
  try {
    std::size_t used = 0;
    v = std::stod(s, &used);
    return used == s.size() && std::isfinite(v);
  } catch (const std::exception&) {
    return false;
  }
}

/// An integer spanning the whole string.
inline bool parse_long(const std::string& s, long& v) {
  try {
    std::size_t used = 0;
    v = std::stol(s, &used);
    return used == s.size();
  } catch (const std::exception&) {
    return false;
  }
}

/// Exactly `count` comma-separated finite numbers (no trailing comma).
inline bool parse_numbers(const std::string& s, std::size_t count, std::vector<double>& v) {
  v.clear();
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    double x;
    if (!parse_number(item, x)) return false;
    v.push_back(x);
  }
  return v.size() == count && !s.empty() && s.back() != ',';
}

}  // namespace grains::io::cli_args
