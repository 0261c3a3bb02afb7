// Material pair mixing and overrides; size distributions and placement.
#include <gtest/gtest.h>

#include <random>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"
#include "sim/laws/material.hpp"
#include "sim/laws/restitution.hpp"
#include "sim/scene/placement.hpp"

namespace grains::sim {
namespace {

TEST(PairTable, MixingRulesAndOverridesInEitherOrder) {
  Material a{"a", 2500, 1e9, 0.25, 0.9, 0.2, 0.0, 0.0};
  Material b{"b", 7800, 2e11, 0.3, 0.5, 0.6, 0.1, 0.0};
  PairOverride o;
  o.a = 1;
  o.b = 0;
  o.friction = 0.33;
  o.restitution = 0.7;
  const PairTable t({a, b}, {o});
  EXPECT_NEAR(t(0, 0).E_eff, 1e9 / (2 * (1 - 0.25 * 0.25)), 1e-3);
  EXPECT_NEAR(t(0, 1).E_eff, 1.0 / ((1 - 0.0625) / 1e9 + (1 - 0.09) / 2e11), 1e-3);
  EXPECT_DOUBLE_EQ(t(0, 1).friction, 0.33);
  EXPECT_DOUBLE_EQ(t(1, 0).friction, 0.33);
  EXPECT_DOUBLE_EQ(t(0, 1).restitution, 0.7);
  EXPECT_DOUBLE_EQ(t(0, 1).rolling_friction, 0.05);  // mean: not overridden
  EXPECT_DOUBLE_EQ(t(1, 1).friction, 0.6);
  EXPECT_DOUBLE_EQ(t(0, 1).damping, damping_for_restitution(0.7));
  EXPECT_TRUE(t.any_friction());
  EXPECT_TRUE(t.any_rolling());
  EXPECT_FALSE(t.any_cohesion());
}

TEST(SizeDistribution, SamplesStayInTheirSupport) {
  std::mt19937_64 rng(5);
  SizeDistribution u;
  u.kind = SizeDistribution::Kind::Uniform;
  u.min = 1e-3;
  u.max = 2e-3;
  const auto ru = sample_radii(u, 20000, rng);
  double mean = 0;
  for (double r : ru) {
    EXPECT_GE(r, 1e-3);
    EXPECT_LE(r, 2e-3);
    mean += r / ru.size();
  }
  EXPECT_NEAR(mean, 1.5e-3, 1e-5);
  SizeDistribution ln;
  ln.kind = SizeDistribution::Kind::LogNormal;
  ln.mean = 1e-3;
  ln.stddev = 1e-4;
  ln.min = 1e-4;
  ln.max = 1e-2;
  const auto rl = sample_radii(ln, 50000, rng);
  double m = 0, m2 = 0;
  for (double r : rl) {
    m += r / rl.size();
    m2 += r * r / rl.size();
  }
  EXPECT_NEAR(m, 1e-3, 5e-6);
  EXPECT_NEAR(std::sqrt(m2 - m * m), 1e-4, 3e-6);
  SizeDistribution d;
  d.kind = SizeDistribution::Kind::Discrete;
  d.values = {1e-3, 2e-3};
  d.weights = {3, 1};
  int small = 0;
  for (double r : sample_radii(d, 40000, rng)) {
    EXPECT_TRUE(r == 1e-3 || r == 2e-3);
    small += r == 1e-3;
  }
  EXPECT_NEAR(small / 40000.0, 0.75, 0.01);
}

TEST(Placement, PolydisperseRandomFillDoesNotOverlapAndStaysInTheRegion) {
  const std::string yaml = R"(
domain: {min: [0, 0, 0], max: [0.02, 0.02, 0.02]}
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
particles:
  - {material: m, count: 400, radius: {distribution: uniform, min: 0.0003, max: 0.0008},
     placement: {type: random_fill, region: {min: [0.001, 0.001, 0.005], max: [0.019, 0.019, 0.019]}, seed: 3}}
  - {material: m, count: 27, radius: 0.0004, placement: {type: lattice, region: {min: [0.0, 0.0, 0.0], max: [0.0025, 0.0025, 0.0025]}, spacing: 0.0008}}
time: {dt_rayleigh: 0.2, end: 0.001}
)";
  auto s = io::make_simulation(io::parse_case(yaml, "t.yaml"));
  const auto& p = s.scene.particles;
  ASSERT_EQ(p.n_owned(), 427u);
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    for (std::size_t j = i + 1; j < p.n_owned(); ++j)
      EXPECT_GE((p.x[i] - p.x[j]).norm(), (p.radius[i] + p.radius[j]) * (1 - 0.01)) << i << " " << j;
  }
}

}  // namespace
}  // namespace grains::sim
