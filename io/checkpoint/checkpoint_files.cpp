// Naming, listing, validation and retention of the checkpoints in a folder.
#include <algorithm>
#include <cstdio>
#include <regex>

#include "io/checkpoint/checkpoint.hpp"

namespace grains::io {

namespace fs = std::filesystem;

std::string checkpoint_name(std::int64_t step) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "checkpoint_%012lld.h5", static_cast<long long>(step));
  return buf;
}

namespace {
// Step of a checkpoint file name, or -1.
std::int64_t step_of(const fs::path& p) {
  static const std::regex re("checkpoint_([0-9]+)\\.h5");
  std::smatch m;
  const std::string name = p.filename().string();
  if (!std::regex_match(name, m, re)) return -1;
  return std::stoll(m[1].str());
}
}  // namespace

std::vector<fs::path> list_checkpoints(const fs::path& dir) {
  std::vector<std::pair<std::int64_t, fs::path>> found;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (const auto s = step_of(it->path()); s >= 0 && it->is_regular_file()) found.emplace_back(s, it->path());
  std::sort(found.begin(), found.end());
  std::vector<fs::path> out;
  for (auto& f : found) out.push_back(std::move(f.second));
  return out;
}

fs::path newest_valid_checkpoint(const fs::path& dir, std::vector<std::string>* skipped) {
  const auto all = list_checkpoints(dir);
  for (auto it = all.rbegin(); it != all.rend(); ++it) {
    try {
      const auto info = checkpoint_info(*it);
      if (info.step != step_of(*it)) throw CheckpointError(it->string() + ": holds step " + std::to_string(info.step));
      return *it;
    } catch (const std::exception& e) {
      if (skipped) skipped->push_back(e.what());
    }
  }
  return {};
}

void prune_checkpoints(const fs::path& dir, int keep) {
  const auto all = list_checkpoints(dir);
  std::error_code ec;
  for (std::size_t k = 0; k + static_cast<std::size_t>(std::max(keep, 1)) < all.size(); ++k) fs::remove(all[k], ec);
  // Temporaries of an interrupted write (hidden ".checkpoint_*.h5.tmp").
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const auto name = it->path().filename().string();
    if (name.rfind(".checkpoint_", 0) == 0 && name.size() > 4 && name.substr(name.size() - 4) == ".tmp") {
      std::error_code ec2;
      fs::remove(it->path(), ec2);
    }
  }
}

std::vector<std::string> remove_checkpoints_after(const fs::path& dir, std::int64_t step) {
  std::vector<std::string> removed;
  for (const auto& p : list_checkpoints(dir))
    if (step_of(p) > step) {
      std::error_code ec;
      if (fs::remove(p, ec)) removed.push_back(p.filename().string());
    }
  return removed;
}

}  // namespace grains::io
