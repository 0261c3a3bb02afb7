// ARKODE runs through io::run: summary.json reports the driver's figures,
// a resumed run continues from a checkpoint (within the tolerance: ARKODE
// restarts its step-size control), and a state ARKODE cannot integrate ends
// the run with IntegrationFailure, not as an output failure.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "io/checkpoint/checkpoint.hpp"
#include "sim/integrate/arkode.hpp"
#include "tests/support/sim_helpers.hpp"
#include "tests/unit/checkpoint/checkpoint_scene.hpp"

namespace grains::test {
namespace {

// A sphere launched sideways on a frictional floor: slides, then rolls.
std::string sliding_case(const std::string& extra_time = "") {
  const double R = 0.001;
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.01, -0.01, -0.001], max: [0.05, 0.01, 0.01]}\ngravity: [0, 0, -9.81]\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0.3)
    << "particles:\n" << single("ball", "m", sim::Vec3(0, 0, R * 0.9995), R, sim::Vec3(0.1, 0, 0))
    << "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}\n"
    << "time: {dt_rayleigh: 0.5, end: 0.01, integrator: arkode, rtol: 1.0e-7, atol: 1.0e-7" << extra_time << "}\n"
    << "output: {vtk: false, progress: false}\ncheckpoint: {every_steps: 50, keep: 10}\n";
  return y.str();
}

io::RunOptions quiet(const fs::path& dir) {
  io::RunOptions o;
  o.out_dir = dir;
  o.quiet = true;
  return o;
}

TEST(ArkodeRun, SummaryReportsTheDriverAndAResumedRunAgrees) {
  TempDir tmp("arkode_run");
  auto full = io::make_simulation(io::parse_case(sliding_case(), "slide.yaml"));
  const auto rf = io::run(full, quiet(tmp.path / "full"));
  ASSERT_GT(rf.steps, 100);
  const std::string summary = read_text(tmp.path / "full" / "summary.json");
  EXPECT_NE(summary.find("\"stage_details\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"drift: arkode.erk(order 4, rtol 1e-07, atol 1e-07"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"accepted_steps\": "), std::string::npos) << summary;
  const auto& st = dynamic_cast<const sim::ArkodeIntegrator&>(*full.pipeline.stages().front()).stats();
  EXPECT_GE(st.steps, rf.steps);  // at least one step per clock step
  EXPECT_EQ(st.projection_evaluations, st.steps);  // friction: springs projected after every step
  EXPECT_GT(st.rhs_evaluations, 4 * st.steps);     // order 4: five stages per step

  auto part = io::make_simulation(io::parse_case(sliding_case(), "slide.yaml"));
  auto opt = quiet(tmp.path / "part");
  opt.restart = tmp.path / "full" / "checkpoints" / io::checkpoint_name(100);
  io::run(part, opt);
  EXPECT_EQ(part.scene.clock.step, full.scene.clock.step);
  const auto& a = full.scene.particles;
  const auto& b = part.scene.particles;
  EXPECT_LT((a.x[0] - b.x[0]).norm(), 1e-9);  // 1e-6 of the radius
  EXPECT_LT((a.v[0] - b.v[0]).norm(), 1e-6 * 0.1);
  EXPECT_LT((a.omega[0] - b.omega[0]).norm() * 0.001, 1e-6 * 0.1);
}

TEST(ArkodeRun, AStateItCannotIntegrateEndsTheRunWithAnIntegrationFailure) {
  TempDir tmp("arkode_fail");
  auto s = io::make_simulation(io::parse_case(sliding_case(), "slide.yaml"));
  s.scene.particles.v[0].x() = std::nan("");
  try {
    io::run(s, quiet(tmp.path));
    FAIL() << "a non-finite state was integrated";
  } catch (const sim::IntegrationFailure& e) {
    EXPECT_NE(std::string(e.what()).find("ARKODE could not continue at t = 0 s"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace grains::test
