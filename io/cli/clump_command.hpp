#pragma once
// `grains clump MESH [--grid N] [--mu 0.25] [-o CLUMP.yaml] [--density RHO]
//                    [--key distance|skeletal] [--no-measure]`
// `args` are the words after `clump`. Returns 0 on success, 1 on bad input
// (the message goes to `err`), 2 on bad usage.

#include <ostream>
#include <string>
#include <vector>

namespace grains::io {

int run_clump_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
const char* clump_command_usage();

}  // namespace grains::io
