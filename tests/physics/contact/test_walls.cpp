// Walls: a silo (inside cylinder + floor) holds a poured bed; a moving
// plane pushes particles with its prescribed velocity.
#include <gtest/gtest.h>

#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

TEST(Walls, CylinderSiloHoldsThePour) {
  const std::string yaml = R"(
domain: {min: [-0.006, -0.006, -0.001], max: [0.006, 0.006, 0.03]}
gravity: [0, 0, -9.81]
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}
particles:
  - {material: m, radius: 0.0005, count: 150, placement: {type: random_fill, region: {min: [-0.0035, -0.0035, 0.0], max: [0.0035, 0.0035, 0.028]}}}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}
  - {type: cylinder, base: [0, 0, 0], axis: [0, 0, 1], radius: 0.005, height: 0.03, material: m}
time: {dt_rayleigh: 0.2, end: 0.15}
)";
  auto s = from_yaml(yaml);
  s.pipeline.initialize(s.scene);
  double worst = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    const auto& p = s.scene.particles;
    for (std::size_t i = 0; i < p.n_owned(); ++i)
      worst = std::max(worst, std::hypot(p.x[i].x(), p.x[i].y()) + p.radius[i] - 0.005);
  }
  EXPECT_EQ(s.scene.lost_particles, 0);
  EXPECT_EQ(s.scene.particles.n_owned(), 150u);
  // Penetration into the silo wall stays a small fraction of the radius.
  EXPECT_LT(worst, 0.05 * 0.0005);
  for (std::size_t i = 0; i < s.scene.particles.n_owned(); ++i) EXPECT_GT(s.scene.particles.x[i].z(), 0.0004);
}

TEST(Walls, MovingPlanePushesAParticleAtItsSpeed) {
  // A frictionless piston moving at 0.1 m/s catches a resting particle; after
  // the impact (e = 1, piston of infinite mass) the particle moves at 0.2 m/s.
  const std::string yaml = R"(
domain: {min: [-0.01, -0.01, -0.01], max: [0.05, 0.01, 0.01]}
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e8, poisson_ratio: 0.3, restitution: 1.0, friction: 0}
particles:
  - {material: m, radius: 0.001, count: 1, placement: {type: lattice, region: {min: [0.002, -0.001, -0.001], max: [0.0045, 0.0015, 0.0015]}}}
walls:
  - {type: plane, point: [0, 0, 0], normal: [1, 0, 0], material: m, velocity: [0.1, 0, 0]}
time: {dt_rayleigh: 0.05, end: 0.03}
)";
  auto s = from_yaml(yaml);
  EXPECT_NE(s.pipeline.stage_names()[1].find("walls.move"), std::string::npos);
  s.pipeline.initialize(s.scene);
  while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
  EXPECT_NEAR(s.scene.walls.of<sim::PlaneWall>()[0].point.x(), 0.1 * s.scene.clock.time, 1e-12);
  EXPECT_NEAR(s.scene.particles.v[0].x(), 0.2, 0.2 * 0.005);
}

}  // namespace
}  // namespace grains::test

namespace grains::test {
namespace {

// Rolling resistance (EPSD, fully mobilised): a sphere rolling on a floor
// feels the torque mu_r R F_n = mu_r R m g against its rotation; rolling
// without slip it decelerates at a = mu_r g / (1 + I/(m R^2)) = 5/7 mu_r g.
// Without rolling friction it keeps rolling at constant speed.
double rolling_deceleration(double mu_r) {
  const double R = 0.001, v0 = 0.05;
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.05, -0.01, -0.001], max: [0.2, 0.01, 0.01]}\ngravity: [0, 0, -9.81]\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0.5, mu_r)
    << "particles:\n" << single("ball", "m", sim::Vec3(0, 0, R * 0.99995), R, sim::Vec3(v0, 0, 0))
    << "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}\n"
    << "time: {dt_rayleigh: 0.1, end: 0.4}\n";
  auto s = from_yaml(y.str());
  s.scene.particles.omega[0] = sim::Vec3(0, v0 / R, 0);  // rolling without slip
  s.pipeline.initialize(s.scene);
  // Let the contact settle, then measure the speed change over a window.
  double t1 = 0, v1 = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    if (t1 == 0 && s.scene.clock.time >= 0.05) {
      t1 = s.scene.clock.time;
      v1 = s.scene.particles.v[0].x();
    }
  }
  return (v1 - s.scene.particles.v[0].x()) / (s.scene.clock.time - t1);
}

TEST(RollingResistance, EpsdDeceleratesARollingSphereAtFiveSeventhsMuRG) {
  const double mu_r = 0.01;
  EXPECT_NEAR(rolling_deceleration(mu_r) / (5.0 / 7.0 * mu_r * 9.81), 1.0, 0.05);
  EXPECT_NEAR(rolling_deceleration(0.0), 0.0, 1e-3);
}

}  // namespace
}  // namespace grains::test
