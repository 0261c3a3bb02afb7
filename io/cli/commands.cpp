#include "io/cli/commands.hpp"

#include <sstream>

namespace grains::io {

std::string format_doc(const sim::EffectDoc& d) {
  std::ostringstream o;
  o << d.name << "    (" << d.section << ")\n  " << d.summary << "\n";
  for (const auto& k : d.keys) {
    o << "  " << k.name << ": " << sim::key_type_name(k.type);
    if (!k.unit.empty()) o << ", " << k.unit;
    if (k.required) o << ", required";
    if (!k.default_value.empty()) o << ", default " << k.default_value;
    const auto r = k.range_text();
    if (!r.empty()) o << ", valid " << r;
    if (!k.choices.empty()) {
      o << ", one of";
      for (const auto& c : k.choices) o << " " << c;
    }
    o << "\n      " << k.doc << "\n";
  }
  return o.str();
}

int run_tool_command(const std::string& cmd, const std::vector<std::string>& args) {
  (void)cmd;
  (void)args;
  return -1;
}

}  // namespace grains::io
