#pragma once
#include <string>
#include <vector>

#include "sim/keys/effect_doc.hpp"

namespace grains::io {

/// Human-readable documentation of one effect's keys.
std::string format_doc(const sim::EffectDoc& d);

/// Tool sub-commands (pw85, clump, ...). Returns -1 when `cmd` is not one.
int run_tool_command(const std::string& cmd, const std::vector<std::string>& args);

}  // namespace grains::io
