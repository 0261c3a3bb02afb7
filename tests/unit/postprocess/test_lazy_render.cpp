// Rendering is a module loaded the first time a picture is asked for
// (postprocess/render/render_module.hpp): a simulation run never maps VTK's
// rendering, OpenGL or X11 libraries, and a picture still comes out right
// once the module is loaded. One test per process (ctest runs each on its
// own), so nothing before it has loaded the module.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"
#include "tests/support/mapped.hpp"
#include "postprocess/render.hpp"

namespace {

namespace fs = std::filesystem;

using grains::test::mapped;

const char* kCase = R"(title: lazy_render
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
gravity: [0, 0, -9.81]
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}
particles:
  - {name: s, material: m, radius: 0.0005, count: 40,
     placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}, seed: 1}}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: m}
time: {dt: 1.0e-5, end: 2.0e-3}
output: {every: 1.0e-3}
)";

}  // namespace

TEST(LazyRender, ARunNeverMapsRenderingAndAPictureLoadsIt) {
  for (const char* lib : {"libgrains_render", "libvtkRenderingOpenGL2", "libvtkRenderingCore", "libGL.", "libX11"})
    ASSERT_FALSE(mapped(lib)) << lib << " is mapped before anything asked for a picture";
  const fs::path dir = fs::temp_directory_path() / ("grains_lazy_render_" + std::to_string(getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "case.yaml") << kCase;
  auto sim = grains::io::make_simulation(grains::io::load_case((dir / "case.yaml").string(), {}));
  grains::io::RunOptions o;
  o.out_dir = dir / "out";
  o.quiet = true;
  grains::io::run(sim, o);
  ASSERT_TRUE(fs::exists(dir / "out" / "particles.pvd"));
  for (const char* lib : {"libgrains_render", "libvtkRenderingOpenGL2", "libvtkRenderingCore", "libGL.", "libX11"})
    EXPECT_FALSE(mapped(lib)) << "a run with VTK output mapped " << lib;

  grains::postprocess::RenderOptions r;
  r.width = 160;
  r.height = 120;
  grains::postprocess::render_frame(dir / "out", -1, r, dir / "frame.png");
  EXPECT_TRUE(mapped("libgrains_render"));
  EXPECT_TRUE(mapped("libvtkRenderingOpenGL2"));
  const auto s = grains::postprocess::png_statistics(dir / "frame.png");
  EXPECT_EQ(s.width, 160);
  EXPECT_EQ(s.height, 120);
  EXPECT_GT(s.variance, 0.0) << "a blank picture";
  std::error_code ec;
  fs::remove_all(dir, ec);
}

// A module that cannot be loaded is an error that says what is missing and
// where it was looked for (in a child process: the first load is cached).
TEST(LazyRender, AModuleThatCannotBeLoadedIsAClearError) {
  EXPECT_EXIT(
      {
        setenv("GRAINS_RENDER_MODULE", "/nonexistent/libgrains_render.so", 1);
        try {
          grains::postprocess::png_statistics("/nonexistent/picture.png");
        } catch (const std::exception& e) {
          std::cerr << e.what();
          std::exit(3);
        }
        std::exit(0);
      },
      testing::ExitedWithCode(3),
      "rendering a picture needs grains's rendering \\(VTK, OpenGL\\) module \\(libgrains_render.so.*"
      "GRAINS_RENDER_MODULE.*/nonexistent/libgrains_render.so");
}
