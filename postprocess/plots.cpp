#include "postprocess/plots.hpp"

#include <cstdlib>
#include <string>
#include <sys/wait.h>
#include <vector>

#ifndef GRAINS_POSTPROCESS_SCRIPTS
#define GRAINS_POSTPROCESS_SCRIPTS "postprocess/scripts"
#endif

namespace grains::postprocess {

namespace fs = std::filesystem;

std::filesystem::path plot_script() {
  if (const char* d = std::getenv("GRAINS_SCRIPTS_DIR"); d && *d) return fs::path(d) / "plot_analysis.py";
  return fs::path(GRAINS_POSTPROCESS_SCRIPTS) / "plot_analysis.py";
}

namespace {
std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
}  // namespace

std::string make_plots(const fs::path& dir) {
  const fs::path script = plot_script();
  if (!fs::exists(script)) return "plotting script '" + script.string() + "' not found (set GRAINS_SCRIPTS_DIR)";
  // Debian's matplotlib belongs to /usr/bin/python3, which a python3 earlier on
  // PATH (pyenv, conda, venv) may not see: try $GRAINS_PYTHON, then Debian's, then PATH's.
  std::vector<std::string> pythons;
  if (const char* p = std::getenv("GRAINS_PYTHON"); p && *p) pythons.emplace_back(p);
  if (fs::exists("/usr/bin/python3")) pythons.emplace_back("/usr/bin/python3");
  pythons.emplace_back("python3");
  std::string why = "python3 not found";
  for (const auto& py : pythons) {
    const std::string cmd = shell_quote(py) + " " + shell_quote(script.string()) + " " + shell_quote(dir.string()) +
                            " > /dev/null";
    const int rc = std::system(cmd.c_str());
    if (rc == -1) continue;
    if (WIFEXITED(rc) && WEXITSTATUS(rc) == 0) return {};
    if (WIFEXITED(rc) && WEXITSTATUS(rc) == 127) continue;
    if (WIFEXITED(rc) && WEXITSTATUS(rc) == 3) {
      why = "python3-matplotlib is not installed";
      continue;
    }
    return "plot_analysis.py failed under " + py + " (exit status " +
           std::to_string(WIFEXITED(rc) ? WEXITSTATUS(rc) : -1) + ")";
  }
  return why;
}

}  // namespace grains::postprocess
