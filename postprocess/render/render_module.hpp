#pragma once
// The rendering module, libgrains_render.so: `grains render`'s offscreen
// pictures (render.cpp) and the PNG statistics, with VTK's rendering,
// OpenGL, X11 and image libraries behind them. It is loaded the first time a
// picture is asked for (postprocess/render_loader.cpp, through
// contact/module_loader.hpp), so that a simulation run never maps those
// libraries (about 10 MB resident per process, and on every MPI rank).
// Its entry points have C linkage and report errors by their message.

extern "C" {
/// render_frame (postprocess/render.hpp). 0 on success; otherwise the
/// message of the error, cut to error_size, in `error`.
using GrainsRenderFrame = int (*)(const char* out_dir, long index, const char* color, int width, int height,
                                  int walls, double wall_opacity, const char* view, const char* png, char* error,
                                  unsigned long error_size);
/// png_statistics (postprocess/render.hpp), as render_frame.
using GrainsPngStatistics = int (*)(const char* png, int* width, int* height, double* mean, double* variance,
                                    unsigned long* distinct_colours, char* error, unsigned long error_size);
}

namespace grains::postprocess {
inline constexpr const char* kGrainsRenderFrameSymbol = "grains_render_frame";
inline constexpr const char* kGrainsPngStatisticsSymbol = "grains_png_statistics";
}  // namespace grains::postprocess
