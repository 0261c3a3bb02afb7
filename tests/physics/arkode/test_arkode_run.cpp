// ARKODE runs through io::run: summary.json reports the driver's figures,
// a resumed run continues from a checkpoint (within the tolerance: ARKODE
// restarts its step-size control), and a state ARKODE cannot integrate ends
// the run with IntegrationFailure, not as an output failure.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

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

namespace grains::test {
namespace {

// Kinetic energy, and whether any pair touches (minimum image in the box).
double kinetic(const sim::Scene& s, bool& touching) {
  const auto& p = s.particles;
  const sim::Vec3 L = s.domain.hi - s.domain.lo;
  double e = 0;
  touching = false;
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    e += 0.5 * p.mass[i] * p.v[i].squaredNorm();
    for (std::size_t j = i + 1; j < p.n_owned(); ++j) {
      sim::Vec3 d = p.x[i] - p.x[j];
      for (int a = 0; a < 3; ++a) d[a] -= L[a] * std::round(d[a] / L[a]);
      touching = touching || d.norm() < p.radius[i] + p.radius[j];
    }
  }
  return e;
}

TEST(ArkodeRun, ElasticGasInAPeriodicBoxKeepsMomentumAndEnergy) {
  // 27 spheres, fully periodic, random velocities (0.2 m/s): they cross the
  // faces many times and collide across them (ghost images follow every
  // trial state). Between collisions the kinetic energy is the initial one.
  const std::string yaml = R"(
domain: {min: [0, 0, 0], max: [0.006, 0.006, 0.006], periodic: true}
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 1.0, friction: 0}
particles:
  - {material: m, radius: 0.0005, count: 27, placement: {type: lattice, region: {min: [0.0005, 0.0005, 0.0005], max: [0.0058, 0.0058, 0.0058]}, spacing: 0.002}}
time: {dt_rayleigh: 0.5, end: 0.05, integrator: arkode, rtol: 1.0e-8, atol: 1.0e-8}
)";
  auto s = from_yaml(yaml);
  auto& p = s.scene.particles;
  ASSERT_EQ(p.n_owned(), 27u);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> n(0.0, 0.2);
  sim::Vec3 mean = sim::Vec3::Zero();
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    p.v[i] = sim::Vec3(n(rng), n(rng), n(rng));
    mean += p.v[i] / 27.0;
  }
  for (std::size_t i = 0; i < p.n_owned(); ++i) p.v[i] -= mean;  // zero total momentum
  s.pipeline.initialize(s.scene);
  bool touching = false;
  const double e0 = kinetic(s.scene, touching);
  ASSERT_FALSE(touching);
  double worst = 0;
  int quiet_samples = 0, contact_samples = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    const double e = kinetic(s.scene, touching);
    if (touching) {
      ++contact_samples;
    } else {
      ++quiet_samples;
      worst = std::max(worst, std::abs(e - e0) / e0);
    }
  }
  sim::Vec3 P = sim::Vec3::Zero();
  for (std::size_t i = 0; i < p.n_owned(); ++i) P += p.mass[i] * p.v[i];
  EXPECT_LT(P.norm(), 1e-12 * p.mass[0] * 0.2);
  EXPECT_GT(contact_samples, 20) << "collisions happened";
  EXPECT_GT(quiet_samples, 20);
  EXPECT_LT(worst, 1e-6);
  EXPECT_EQ(s.scene.lost_particles, 0);
  for (std::size_t i = 0; i < p.n_owned(); ++i) EXPECT_TRUE(s.scene.domain.contains(p.x[i]));
}

}  // namespace
}  // namespace grains::test
