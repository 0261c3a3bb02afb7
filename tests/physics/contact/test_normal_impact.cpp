// Head-on impacts against the analytic Hertz solution and the target
// restitution (../shared/REFERENCES.md: Hertz formulas; Chung & Ooi,
// Granular Matter 13, 2011, test 1: glass spheres E = 48 GPa, nu = 0.2,
// rho = 2800 kg/m^3, R = 10 mm, +-10 m/s: delta_max ~ 274 um, t_c ~ 40.3 us).
#include <gtest/gtest.h>

#include "sim/laws/restitution.hpp"
#include "tests/physics/contact/impact.hpp"

namespace grains::test {
namespace {

TEST(NormalImpact, ChungOoiGlassHertzContactTimeAndOverlap) {
  // e = 1: the Hertz formulas are for elastic impact.
  const double E = 48e9, nu = 0.2, rho = 2800, R = 0.01, v = 10;
  const auto r = impact(false, E, nu, rho, R, v, 1.0, 2000);
  const double m = rho * 4.0 / 3.0 * M_PI * R * R * R, mstar = m / 2, Estar = E / (2 * (1 - nu * nu)), Rstar = R / 2;
  const double vrel = 2 * v;
  const double dmax = std::pow(15 * mstar * vrel * vrel / (16 * Estar * std::sqrt(Rstar)), 0.4);
  const double tc = 2.9432 * dmax / vrel;
  EXPECT_NEAR(r.max_overlap / dmax, 1.0, 0.005);
  EXPECT_NEAR(r.contact_time / tc, 1.0, 0.005);
  // The published figures of the benchmark.
  EXPECT_NEAR(dmax, 274e-6, 2e-6);
  EXPECT_NEAR(tc, 40.3e-6, 0.2e-6);
  EXPECT_NEAR(r.restitution, 1.0, 1e-3);
}

TEST(NormalImpact, SphereWallHertzContactTime) {
  const double E = 48e9, nu = 0.2, rho = 2800, R = 0.01, v = 3;
  const auto r = impact(true, E, nu, rho, R, v, 1.0, 2000);
  const double m = rho * 4.0 / 3.0 * M_PI * R * R * R, Estar = E / (2 * (1 - nu * nu));
  const double dmax = std::pow(15 * m * v * v / (16 * Estar * std::sqrt(R)), 0.4);
  EXPECT_NEAR(r.max_overlap / dmax, 1.0, 0.005);
  EXPECT_NEAR(r.contact_time / (2.9432 * dmax / v), 1.0, 0.005);
}

class Restitution : public ::testing::TestWithParam<std::tuple<bool, double>> {};

TEST_P(Restitution, AchievedWithinOnePercentOfTarget) {
  const auto [wall, e] = GetParam();
  // Soft and stiff, slow and fast: the calibration is independent of all of them.
  for (const double E : {1e7, 1e9})
    for (const double v : {0.5, 5.0}) {
      const auto r = impact(wall, E, 0.3, 2500, 0.001, v, e, 400);
      EXPECT_NEAR(r.restitution / e, 1.0, 0.01) << (wall ? "sphere-wall" : "sphere-sphere") << " E=" << E << " v=" << v;
    }
}

INSTANTIATE_TEST_SUITE_P(Targets, Restitution,
                         ::testing::Combine(::testing::Bool(), ::testing::Values(0.1, 0.5, 0.9)));

TEST(RestitutionCalibration, InverseOfTheDimensionlessImpact) {
  for (const double e : {0.05, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
    const double a = sim::damping_for_restitution(e);
    EXPECT_NEAR(sim::restitution_for_damping(a), e, 1e-7);
  }
  EXPECT_EQ(sim::damping_for_restitution(1.0), 0.0);
  EXPECT_THROW(sim::damping_for_restitution(0.0), std::invalid_argument);
  EXPECT_THROW(sim::damping_for_restitution(1.5), std::invalid_argument);
}

TEST(RestitutionCalibration, LiggghtsFormulaMissesTheTargetWhenClamped) {
  // REFERENCES.md: clamping F_n >= 0 raises the achieved e of the
  // LIGGGHTS/EDEM damping (target 0.5 -> ~0.55, 0.1 -> ~0.25). Our
  // calibration is what makes the target exact.
  EXPECT_GT(sim::restitution_for_damping(sim::liggghts_damping(0.5)), 0.52);
  EXPECT_GT(sim::restitution_for_damping(sim::liggghts_damping(0.1)), 0.15);
}

}  // namespace
}  // namespace grains::test
