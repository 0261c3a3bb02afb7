// A clump pour restarted from a checkpoint continues bitwise identically:
// the /bodies group carries every body array (io/checkpoint).
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "io/checkpoint/checkpoint.hpp"
#include "tests/physics/clump/clump_cases.hpp"
#include "tests/unit/checkpoint/checkpoint_scene.hpp"

namespace grains::test {
namespace {

std::string pour_case() {
  return std::string(GRAINS_SOURCE_DIR) + "/cases/pour_clumps/case.yaml";
}

std::vector<std::string> small_pour() {
  return {"particles.0.count=40", "particles.0.shape.grid=6", "time.end=0.03", "checkpoint.every_steps=1000",
          "checkpoint.keep=10", "output.progress=false"};
}

io::RunOptions quiet(const fs::path& dir) {
  io::RunOptions o;
  o.out_dir = dir;
  o.quiet = true;
  return o;
}

void expect_same_bodies(sim::BodyStore& a, sim::BodyStore& b) {
  ASSERT_EQ(a.size(), b.size());
  std::map<std::string, std::string> fa;
  a.visit_fields([&](const char* name, const char*, auto& vec) { fa[name] = bytes(vec); });
  b.visit_fields([&](const char* name, const char*, auto& vec) {
    EXPECT_TRUE(fa.at(name) == bytes(vec)) << "body field '" << name << "' differs";
  });
}

TEST(ClumpRestart, PourContinuesBitwiseFromACheckpoint) {
  (void)clump_test_dir();
  TempDir tmp("clump_restart");
  auto full = io::make_simulation(io::load_case(pour_case(), small_pour()));
  const auto rf = io::run(full, quiet(tmp.path / "full"));
  ASSERT_GT(rf.steps, 2000);
  ASSERT_EQ(full.scene.bodies.size(), 40u);
  EXPECT_GT(full.scene.neighbors.stats().builds, 5);
  // Contacts happened: some balls of different bodies touch at the end.
  auto part = io::make_simulation(io::load_case(pour_case(), small_pour()));
  auto opt = quiet(tmp.path / "part");
  opt.restart = tmp.path / "full" / "checkpoints" / io::checkpoint_name(2000);
  io::run(part, opt);
  expect_same_state(full.scene, part.scene);
  expect_same_bodies(full.scene.bodies, part.scene.bodies);
  // The bodies file series is written next to the particles.
  EXPECT_TRUE(fs::exists(tmp.path / "full" / "bodies.pvd"));
  EXPECT_TRUE(fs::exists(tmp.path / "full" / "frames" / "bodies_000000.vtu"));
}

}  // namespace
}  // namespace grains::test
