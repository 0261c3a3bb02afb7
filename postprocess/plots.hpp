#pragma once
// PNG plots of an analysis folder, drawn by postprocess/scripts/plot_analysis.py
// (python3 with Debian's python3-matplotlib).
#include <filesystem>
#include <string>

namespace grains::postprocess {

/// The plotting script: $GRAINS_SCRIPTS_DIR/plot_analysis.py when set, else the
/// one in the source tree this program was built from.
std::filesystem::path plot_script();

/// Runs the script on an analysis folder; returns an empty string on success,
/// otherwise why no plots were made (no python3, no matplotlib, script error).
std::string make_plots(const std::filesystem::path& analysis_dir);

}  // namespace grains::postprocess
