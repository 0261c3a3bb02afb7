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
/// step) before `step` from its current content. The kept rows go to a
/// hidden file first, renamed over `file` (atomic): a run killed meanwhile
/// leaves the old content whole, not a truncated file.
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
  if (keep.empty()) keep.push_back(header);
  std::string hidden = file.filename().string();
  hidden.insert(hidden.begin(), '.');
  hidden.append(".tmp");
  const std::filesystem::path tmp = file.parent_path() / hidden;
  {
    std::ofstream t(tmp, std::ios::trunc);
    for (const auto& l : keep) t << l << "\n";
    t.flush();
    if (!t) throw std::runtime_error("cannot write '" + tmp.string() + "' (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) throw std::runtime_error("cannot replace '" + file.string() + "': " + ec.message());
  out.open(file, std::ios::app);
  if (!out) throw std::runtime_error("cannot write '" + file.string() + "'");
}

}  // namespace grains::io
