#pragma once
// A fresh, unique folder under the system temp folder, removed with its
// contents when the test ends.
#include <stdlib.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace grains::test {

struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& name = "test") {
    std::string t = (std::filesystem::temp_directory_path() / ("grains_" + name + "_XXXXXX")).string();
    path = ::mkdtemp(t.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

}  // namespace grains::test
