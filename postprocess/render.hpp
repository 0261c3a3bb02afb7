#pragma once
// A picture of one frame, rendered offscreen with VTK: spheres as sphere
// glyphs scaled by their radius, ellipsoids as sphere glyphs scaled by their
// semi-axes and rotated by their orientation quaternion, clump balls as the
// spheres they are, coloured by a point field through a colour bar; walls
// translucent.
//
// Debian's VTK renders through GLX only (no EGL or OSMesa build), so it needs
// an X server. When DISPLAY is unset or cannot be opened, render_frame starts
// a private Xvfb (Debian package xvfb) for the duration of the call and stops
// it afterwards; otherwise it uses DISPLAY (render/headless_display.hpp).
//
// The work is done in the rendering module, libgrains_render.so
// (render/render_module.hpp), loaded on the first call: from
// $GRAINS_RENDER_MODULE if set, else where the build put it, else beside the
// program. A module that cannot be loaded is an error naming the paths tried.
#include <filesystem>
#include <string>

namespace grains::postprocess {

struct RenderOptions {
  /// Point field to colour by: a scalar array (radius, coordination, material,
  /// id), or a vector array by magnitude (velocity, force, angular_velocity,
  /// semi_axes), or one component with a suffix: velocity:z, force:x, ...
  std::string color = "radius";
  int width = 1200, height = 900;
  bool walls = true;
  double wall_opacity = 0.2;
  /// Camera: "iso" (oblique, z up), "x", "y" (side views) or "z" (from above).
  std::string view = "iso";
};

/// Renders frame `index` (negative counts from the end) of an output folder
/// into a PNG. Throws std::runtime_error with a message that says what is
/// missing (frame, field, display).
void render_frame(const std::filesystem::path& out_dir, long index, const RenderOptions& o,
                  const std::filesystem::path& png);

struct ImageStats {
  int width = 0, height = 0;
  double mean = 0, variance = 0;  // over all RGB channel values, 0..255
  std::size_t distinct_colours = 0;
};

/// Pixel statistics of a PNG (to check that a picture is not blank).
ImageStats png_statistics(const std::filesystem::path& png);

}  // namespace grains::postprocess
