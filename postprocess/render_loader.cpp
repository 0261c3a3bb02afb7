// render.hpp's functions, run by the rendering module (render/render_module.hpp),
// loaded the first time a picture is asked for.
#include <stdexcept>
#include <string>

#include "contact/module_loader.hpp"
#include "postprocess/render.hpp"
#include "postprocess/render/render_module.hpp"

namespace grains::postprocess {

namespace {

// Looked up once per process (module_loader.hpp).
template <class Fn>
Fn render_entry(const char* symbol) {
#ifdef GRAINS_RENDER_MODULE_PATH
  const char* build_path = GRAINS_RENDER_MODULE_PATH;
#else
  const char* build_path = nullptr;
#endif
  return reinterpret_cast<Fn>(module_symbol({"GRAINS_RENDER_MODULE", build_path, "libgrains_render.so", symbol,
                                             "rendering a picture", "rendering (VTK, OpenGL)"}));
}

}  // namespace

void render_frame(const std::filesystem::path& out_dir, long index, const RenderOptions& o,
                  const std::filesystem::path& png) {
  const auto fn = render_entry<GrainsRenderFrame>(kGrainsRenderFrameSymbol);
  char error[4096];
  if (fn(out_dir.c_str(), index, o.color.c_str(), o.width, o.height, o.walls ? 1 : 0, o.wall_opacity, o.view.c_str(),
         png.c_str(), error, sizeof error) != 0)
    throw std::runtime_error(error);
}

ImageStats png_statistics(const std::filesystem::path& png) {
  const auto fn = render_entry<GrainsPngStatistics>(kGrainsPngStatisticsSymbol);
  char error[4096];
  ImageStats s;
  unsigned long distinct = 0;
  if (fn(png.c_str(), &s.width, &s.height, &s.mean, &s.variance, &distinct, error, sizeof error) != 0)
    throw std::runtime_error(error);
  s.distinct_colours = distinct;
  return s;
}

}  // namespace grains::postprocess
