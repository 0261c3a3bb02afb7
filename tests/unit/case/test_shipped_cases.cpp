// Every shipped case (cases/*/case.yaml) parses and sets up as it is: its
// files (meshes, clump meshes) are found relative to it, it has grains (or
// inserts them), its particles start
// clear of its walls, and `grains check`'s description names its mesh walls.
#include <gtest/gtest.h>

#include <filesystem>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"

namespace grains::test {
namespace {

namespace fs = std::filesystem;

TEST(ShippedCases, EveryCaseSetsUp) {
  int n = 0;
  for (const auto& dir : fs::directory_iterator(fs::path(GRAINS_SOURCE_DIR) / "cases")) {
    const fs::path file = dir.path() / "case.yaml";
    if (!fs::exists(file)) continue;
    SCOPED_TRACE(file.string());
    io::Simulation s;
    ASSERT_NO_THROW(s = io::make_simulation(io::load_case(file.string(), {})));
    // Grains from the start, or inserted during the run (cases/adhesive_deposition).
    EXPECT_TRUE(s.scene.particles.n_owned() > 0 || !s.c.scene.insertions.empty());
    const std::string d = io::describe(s);
    for (const auto& w : s.scene.walls.of<sim::MeshWall>()) {
      EXPECT_GT(w.surface->triangles(), 0u);
      EXPECT_NE(d.find("mesh wall '" + w.name + "'"), std::string::npos) << d;
    }
    ++n;
  }
  EXPECT_GE(n, 9);
}

}  // namespace
}  // namespace grains::test
