#pragma once
// `grains analyze` and `grains render`: the postprocess library on a run's
// output folder. Both return 0 on success, 2 for bad arguments or input,
// 1 when the analysis or rendering itself fails.
#include <ostream>
#include <string>
#include <vector>

namespace grains::io {

/// grains analyze OUTDIR [--frame N | --time T] [--region xmin,ymin,zmin,xmax,ymax,zmax] [-o DIR] ...
/// (see the usage text in analyze_command.cpp)
int run_analyze_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

/// grains render OUTDIR [--frame N] [--color FIELD] [--view iso|x|y|z] [--size WxH] [--no-walls] -o PNG
int run_render_command(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace grains::io
