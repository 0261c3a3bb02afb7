#pragma once
// `grains repose`: the dynamic angle of repose of the free surface of a bed in
// a rotating drum, over the frames of a run (postprocess/surface_angle.hpp
// has the method). Returns 0 on success, 2 for bad arguments or input, 1 when
// no frame could be measured or the results cannot be written.
#include <ostream>
#include <string>
#include <vector>

namespace grains::io {

/// grains repose OUTDIR [--axis x|y] [--centre X,Y,Z] [--radius R] [--column W] [--span F]
///                      [--from T] [--to T] [-o DIR]   (see the usage text in repose_command.cpp)
int run_repose_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

/// The usage text of `grains repose -h`.
const char* repose_command_usage();

}  // namespace grains::io
