// Energy conservation with e = 1 and no friction: velocity Verlet is
// symplectic, so the total energy (kinetic + Hertz elastic 2/5 K d^{5/2})
// must stay within a bounded band over many collisions, not drift.
#include <gtest/gtest.h>

#include <random>

#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

double total_energy(const sim::Scene& s) {
  const auto& p = s.particles;
  double e = 0;
  for (std::size_t i = 0; i < p.n_owned(); ++i) e += 0.5 * p.mass[i] * p.v[i].squaredNorm();
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    for (std::size_t j = i + 1; j < p.n_owned(); ++j) {
      const double d = p.radius[i] + p.radius[j] - (p.x[i] - p.x[j]).norm();
      if (d <= 0) continue;
      const auto& pp = s.pairs(p.material[i], p.material[j]);
      const double R = p.radius[i] * p.radius[j] / (p.radius[i] + p.radius[j]);
      e += 0.4 * (4.0 / 3.0) * pp.E_eff * std::sqrt(R) * std::pow(d, 2.5);
    }
    for (const auto& w : s.walls.of<sim::PlaneWall>()) {
      const double d = p.radius[i] - w.normal.dot(p.x[i] - w.point);
      if (d <= 0) continue;
      const auto& pp = s.pairs(p.material[i], w.material);
      e += 0.4 * (4.0 / 3.0) * pp.E_eff * std::sqrt(p.radius[i]) * std::pow(d, 2.5);
    }
  }
  return e;
}

TEST(Energy, ElasticFrictionlessGasConservesEnergy) {
  const std::string yaml = R"(
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 1.0, friction: 0}
particles:
  - {material: m, radius: 0.0005, count: 64, placement: {type: lattice, region: {min: [0.0005, 0.0005, 0.0005], max: [0.0095, 0.0095, 0.0095]}, spacing: 0.0022}}
walls:
  - {type: plane, point: [0, 0, 0], normal: [1, 0, 0], material: m}
  - {type: plane, point: [0.01, 0, 0], normal: [-1, 0, 0], material: m}
  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], material: m}
  - {type: plane, point: [0, 0.01, 0], normal: [0, -1, 0], material: m}
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}
  - {type: plane, point: [0, 0, 0.01], normal: [0, 0, -1], material: m}
time: {dt_rayleigh: 0.1, end: 0.2}
)";
  auto s = from_yaml(yaml);
  auto& p = s.scene.particles;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n(0.0, 0.2);
  for (std::size_t i = 0; i < p.n_owned(); ++i) p.v[i] = sim::Vec3(n(rng), n(rng), n(rng));
  s.pipeline.initialize(s.scene);
  const double e0 = total_energy(s.scene);
  double worst = 0;
  long contacts_seen = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    if (s.scene.clock.step % 50 == 0) {
      worst = std::max(worst, std::abs(total_energy(s.scene) - e0) / e0);
      for (std::size_t i = 0; i < p.n_owned(); ++i)
        if (p.f[i].squaredNorm() > 0) ++contacts_seen;
    }
  }
  // Each particle meets ~0.2 m/s * 0.2 s / 1.2 mm ~ 30 others or walls: many collisions.
  EXPECT_GT(contacts_seen, 500);
  // Stated bound: relative energy error below 1e-3 at dt = 0.1 Rayleigh times.
  EXPECT_LT(worst, 1e-3);
  EXPECT_NEAR(total_energy(s.scene) / e0, 1.0, 1e-3);
}

}  // namespace
}  // namespace grains::test
