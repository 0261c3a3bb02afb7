#include "io/cli/commands.hpp"

#include <fstream>
#include <iostream>
#include <sstream>

#include "io/cli/clump_command.hpp"
#include "io/cli/pw85_command.hpp"
#include "io/cli/analyze_command.hpp"
#include "io/cli/repose_command.hpp"

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
  if (cmd == "pw85") {
    if (args.size() > 1 || (args.size() == 1 && args[0].size() > 1 && args[0][0] == '-')) {
      std::cerr << "usage: grains pw85 [FILE]   (CSV with header q1_0..q1_5,q2_0..q2_5,r_0,r_1,r_2; stdin without FILE)\n";
      return 2;
    }
    if (args.empty() || args[0] == "-") return run_pw85_batch(std::cin, std::cout, std::cerr);
    std::ifstream in(args[0]);
    if (!in) {
      std::cerr << "grains pw85: cannot open '" << args[0] << "'\n";
      return 2;
    }
    return run_pw85_batch(in, std::cout, std::cerr);
  }
  if (cmd == "clump") return run_clump_command(args, std::cout, std::cerr);
  if (cmd == "analyze") return run_analyze_command(args, std::cout, std::cerr);
  if (cmd == "render") return run_render_command(args, std::cout, std::cerr);
  if (cmd == "repose") return run_repose_command(args, std::cout, std::cerr);
  return -1;
}

}  // namespace grains::io
