#pragma once
// Whether this process has a library mapped (/proc/self/maps), for the tests
// of the modules loaded on first use (OpenVDB, rendering).
#include <fstream>
#include <sstream>
#include <string>

namespace grains::test {

inline bool mapped(const std::string& lib) {
  std::ifstream f("/proc/self/maps");
  std::stringstream s;
  s << f.rdbuf();
  return s.str().find(lib) != std::string::npos;
}

}  // namespace grains::test
