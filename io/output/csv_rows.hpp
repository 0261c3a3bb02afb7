#pragma once
// CSV series that a restart continues: the rows written before the restored
// step are kept, the rest dropped (they will be written again).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace grains::io {

/// Opens `file` for writing with its header and the rows (first column: the
/// step) before `step` from its current content.
inline void reopen_before(std::ofstream& out, const std::filesystem::path& file, const std::string& header,
                          std::int64_t step) {
  std::vector<std::string> keep;
  {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      if (keep.empty()) {
        keep.push_back(line);  // header
        continue;
      }
      if (std::stoll(line.substr(0, line.find(','))) < step) keep.push_back(line);
    }
  }
  out.open(file, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write '" + file.string() + "'");
  if (keep.empty()) keep.push_back(header);
  for (const auto& l : keep) out << l << "\n";
}

}  // namespace grains::io
