// The entry points of libgrains_render.so (render_module.hpp).
#include "postprocess/render/render_module.hpp"

#include <cstring>
#include <exception>
#include <string>

#include "postprocess/render.hpp"

namespace {

int report(const char* what, char* error, unsigned long size) {
  if (size > 0) {
    std::strncpy(error, what, size - 1);
    error[size - 1] = '\0';
  }
  return 1;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int grains_render_frame(
    const char* out_dir, long index, const char* color, int width, int height, int walls, double wall_opacity,
    const char* view, const char* png, char* error, unsigned long error_size) {
  try {
    grains::postprocess::RenderOptions o;
    o.color = color;
    o.width = width;
    o.height = height;
    o.walls = walls != 0;
    o.wall_opacity = wall_opacity;
    o.view = view;
    grains::postprocess::render_frame(out_dir, index, o, png);
    return 0;
  } catch (const std::exception& e) {
    return report(e.what(), error, error_size);
  } catch (...) {
    return report("rendering failed with an unknown error", error, error_size);
  }
}

extern "C" __attribute__((visibility("default"))) int grains_png_statistics(
    const char* png, int* width, int* height, double* mean, double* variance, unsigned long* distinct_colours,
    char* error, unsigned long error_size) {
  try {
    const auto s = grains::postprocess::png_statistics(png);
    *width = s.width;
    *height = s.height;
    *mean = s.mean;
    *variance = s.variance;
    *distinct_colours = s.distinct_colours;
    return 0;
  } catch (const std::exception& e) {
    return report(e.what(), error, error_size);
  } catch (...) {
    return report("reading the picture failed with an unknown error", error, error_size);
  }
}
