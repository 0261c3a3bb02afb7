#pragma once
// view.py beside particles.pvd: a ParaView Python state that opens the run
// ready to look at (docs/paraview.md).
#include <filesystem>

namespace grains::io {

/// Writes OUT/view.py (atomically: a temporary file renamed over it).
/// Throws std::runtime_error when the file cannot be written.
void write_paraview_state(const std::filesystem::path& out_dir);

/// The script's text.
const char* paraview_state_script();

}  // namespace grains::io
