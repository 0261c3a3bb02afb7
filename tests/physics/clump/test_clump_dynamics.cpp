// Rigid clumps (sim/integrate/clump_bodies.hpp): a dimer at rest on a floor,
// momentum and angular momentum in a frictionless elastic collision of two
// clumps, same-body pairs left out of the neighbour lists, mixed scenes, and
// the pipeline of a sphere-only scene untouched by clumps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "contact/sphere.hpp"
#include "sim/laws/ellipsoid_pair_stage.hpp"
#include "tests/physics/clump/clump_cases.hpp"

namespace grains::test {
namespace {

constexpr double kRho = 2500, kE = 1e7, kNu = 0.3;

std::string box_walls(double w) {
  std::ostringstream o;
  o << "walls:\n"
    << "  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain}\n"
    << "  - {type: plane, name: x0, point: [0, 0, 0], normal: [1, 0, 0], material: grain}\n"
    << "  - {type: plane, name: x1, point: [" << w << ", 0, 0], normal: [-1, 0, 0], material: grain}\n"
    << "  - {type: plane, name: y0, point: [0, 0, 0], normal: [0, 1, 0], material: grain}\n"
    << "  - {type: plane, name: y1, point: [0, " << w << ", 0], normal: [0, -1, 0], material: grain}\n";
  return o.str();
}

// A dimer (balls of radius a, bond a: aspect ratio 1.5) dropped flat (bond
// horizontal) on a floor settles on both balls, level, with the Hertz
// overlap that carries half the body's weight on each ball: gravity acts
// once, on the body, and the balls' contacts use the body's mass.
TEST(ClumpDynamics, DimerFallingFlatRestsOnBothBalls) {
  const double a = 0.001;
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.01, -0.01, -0.001], max: [0.01, 0.01, 0.01]}\n"
    << "gravity: [0, 0, -9.81]\nmaterials:\n"
    << material("grain", kRho, kE, kNu, 0.5, 0.5)
    << "particles:\n  - name: dimer\n    material: grain\n    radius: " << 1.5 * a << "\n    count: 1\n"
    << "    shape: {type: clump, file: " << dimer_file(a, a) << ", orientation: [1, 0, 0, 0]}\n"
    << "    placement: {type: lattice, region: {min: [-0.0015, -0.0015, 0.0015], max: [0.00225, 0.00225, 0.00525]}}\n"
    << "walls:\n  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain}\n"
    << "time: {dt_rayleigh: 0.2, end: 0.4}\n";
  auto s = from_yaml(y.str());
  auto& sc = s.scene;
  ASSERT_EQ(sc.bodies.size(), 1u);
  ASSERT_EQ(sc.particles.n_owned(), 2u);
  EXPECT_NEAR(sc.bodies.x[0].z(), 0.003, 1e-12);
  run_to_end(s);
  const auto& p = sc.particles;
  const auto& b = sc.bodies;
  // At rest.
  EXPECT_LT(b.v[0].norm(), 1e-4);
  EXPECT_LT(b.omega[0].norm(), 1e-2);
  // Level: the bond (body axis 1, the smallest moment) stays horizontal.
  const sim::Vec3 bond = b.orientation[0].toRotationMatrix().col(0);
  EXPECT_LT(std::abs(bond.z()), 1e-6);
  // Both balls touch the floor with the overlap of half the weight each:
  // M g / 2 = K delta^{3/2}, K = 4/3 E* sqrt(a), E* = E / (2 (1 - nu^2)).
  const double M = b.mass[0];
  EXPECT_NEAR(M, kRho * 2.25 * M_PI * a * a * a, 1e-3 * M);  // union of the two balls, analytic
  const double K = 4.0 / 3.0 * kE / (2 * (1 - kNu * kNu)) * std::sqrt(a);
  const double delta = std::pow(M * 9.81 / 2 / K, 2.0 / 3.0);
  for (std::size_t i = 0; i < 2; ++i) {
    const double overlap = p.radius[i] - p.x[i].z();
    EXPECT_GT(overlap, 0) << "ball " << i << " does not touch the floor";
    EXPECT_NEAR(overlap, delta, 0.01 * delta) << "ball " << i;
  }
}

// Two cube clumps (mesh decomposed at load time) collide obliquely with
// restitution 1, no friction, no gravity, no walls: every ball force is
// central, so total momentum and angular momentum are conserved to rounding.
TEST(ClumpDynamics, ElasticFrictionlessCollisionConservesMomentumAndAngularMomentum) {
  std::ostringstream y;
  y.precision(17);
  auto set = [&](const char* name, double x, double z, double vx, int seed) {
    y << "  - name: " << name << "\n    material: grain\n    radius: 0.001\n    count: 1\n    velocity: [" << vx
      << ", 0, 0]\n    shape: {type: clump, mesh: " << cube_mesh() << ", grid: 6}\n"
      << "    placement: {type: random_fill, region: {min: [" << x - 0.00101 << ", -0.00101, " << z - 0.00101
      << "], max: [" << x + 0.00101 << ", 0.00101, " << z + 0.00101 << "]}, seed: " << seed << "}\n";
  };
  (void)clump_test_dir();
  y << "domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}\nmaterials:\n"
    << material("grain", kRho, kE, kNu, 1.0, 0.0) << "particles:\n";
  set("left", -0.0025, 0.0004, 0.5, 3);
  set("right", 0.0025, -0.0004, -0.5, 5);
  y << "time: {dt_rayleigh: 0.1, end: 0.012}\n";
  auto s = from_yaml(y.str());
  auto& sc = s.scene;
  ASSERT_EQ(sc.bodies.size(), 2u);
  s.pipeline.initialize(sc);
  const sim::Vec3 P0 = total_momentum(sc), L0 = body_angular_momentum(sc);
  const double v0 = sc.bodies.v[0].norm();
  double e0 = 0;
  for (std::size_t k = 0; k < 2; ++k) e0 += 0.5 * sc.bodies.mass[k] * sc.bodies.v[k].squaredNorm();
  while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
  const sim::Vec3 P1 = total_momentum(sc), L1 = body_angular_momentum(sc);
  const double pscale = sc.bodies.mass[0] * v0;
  const double lscale = pscale * 0.003;
  EXPECT_LT((P1 - P0).norm(), 1e-12 * pscale) << "P0 " << P0.transpose() << " P1 " << P1.transpose();
  EXPECT_LT((L1 - L0).norm(), 1e-12 * lscale) << "L0 " << L0.transpose() << " L1 " << L1.transpose();
  // They did collide (and apart again: no ball pair touches), and spin now.
  EXPECT_GT((sc.bodies.v[0] - sim::Vec3(0.5, 0, 0)).norm(), 0.1 * v0);
  EXPECT_GT(sc.bodies.omega[0].norm(), 1.0);
  const auto& p = sc.particles;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    for (std::size_t j = i + 1; j < p.n_owned(); ++j)
      if (p.body[i] != p.body[j]) {
        ASSERT_GT((p.x[i] - p.x[j]).norm(), p.radius[i] + p.radius[j]);
      }
  // Elastic: the kinetic energy (translation + rotation) comes back.
  double e1 = 0;
  for (std::size_t k = 0; k < 2; ++k) e1 += 0.5 * sc.bodies.mass[k] * sc.bodies.v[k].squaredNorm() +
                                            0.5 * sc.bodies.omega[k].dot(sc.bodies.angular_momentum[k]);
  EXPECT_NEAR(e1, e0, 2e-3 * e0);
}

// A mixed pour: spheres, ellipsoids, cube clumps and dimers in one box. No
// pair of balls of one body is ever in the list; every touching pair of
// different bodies is; nothing blows up or leaks; ellipsoids meet clump balls.
TEST(ClumpDynamics, MixedPourListsNoSameBodyPairsAndEveryTouchingPair) {
  (void)clump_test_dir();
  const double w = 0.006;
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.001, -0.001, -0.001], max: [0.007, 0.007, 0.03]}\ngravity: [0, 0, -9.81]\nmaterials:\n"
    << material("grain", kRho, kE, kNu, 0.5, 0.5) << "particles:\n";
  const char* shapes[] = {"{type: sphere}", "{type: ellipsoid, aspect_ratio: 2}",
                          "{type: clump, grid: 6, mesh: CUBE}", "{type: clump, file: DIMER}"};
  const double lo[] = {0.0, 0.007, 0.014, 0.021};
  for (int k = 0; k < 4; ++k) {
    std::string sh = shapes[k];
    if (auto at = sh.find("CUBE"); at != std::string::npos) sh.replace(at, 4, cube_mesh());
    if (auto at = sh.find("DIMER"); at != std::string::npos) sh.replace(at, 5, dimer_file(0.0004, 0.0004));
    y << "  - {name: s" << k << ", material: grain, radius: 0.0006, count: 12, shape: " << sh
      << ", placement: {type: random_fill, seed: " << 11 + k << ", region: {min: [0, 0, " << lo[k] << "], max: [" << w
      << ", " << w << ", " << lo[k] + 0.0065 << "]}}}\n";
  }
  y << box_walls(w) << "time: {dt_rayleigh: 0.2, end: 0.3}\n";
  auto s = from_yaml(y.str());
  auto& sc = s.scene;
  ASSERT_EQ(sc.bodies.size(), 24u);
  const std::size_t n0 = sc.particles.n_owned();
  s.pipeline.initialize(sc);
  int ellipsoid_ball = 0;
  while (sc.clock.step < sc.clock.n_steps) {
    s.pipeline.step(sc);
    if (sc.clock.step % 500 != 0) continue;
    const auto& p = sc.particles;
    const auto& nl = sc.neighbors;
    std::set<std::pair<std::int64_t, std::int64_t>> listed;
    for (std::size_t i = 0; i + 1 < nl.row_start.size(); ++i)
      for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        const auto j = nl.partner[k];
        ASSERT_FALSE(p.body[i] >= 0 && p.body[i] == p.body[j]) << "same-body pair in the list";
        listed.insert({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])});
        double lambda = -1;
        contact::ContactGeometry g;
        const bool e_ball = (p.shape[i] == sim::kEllipsoid && p.body[j] >= 0) ||
                            (p.shape[j] == sim::kEllipsoid && p.body[i] >= 0);
        if (e_ball && sim::shape_pair_geometry(p, i, j, lambda, g)) ++ellipsoid_ball;
      }
    for (std::size_t i = 0; i < p.n_owned(); ++i)
      for (std::size_t j = i + 1; j < p.n_owned(); ++j) {
        if (p.body[i] >= 0 && p.body[i] == p.body[j]) continue;
        if ((p.x[i] - p.x[j]).norm() < p.radius[i] + p.radius[j]) {
          ASSERT_TRUE(listed.count({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])}))
              << "touching pair " << p.id[i] << ", " << p.id[j] << " missing at step " << sc.clock.step;
        }
      }
  }
  EXPECT_EQ(sc.particles.n_owned(), n0);
  EXPECT_EQ(sc.lost_particles, 0);
  double vmax = 0;
  for (std::size_t i = 0; i < sc.particles.n_owned(); ++i) vmax = std::max(vmax, sc.particles.v[i].norm());
  EXPECT_LT(vmax, 0.05);  // settled, nothing blew up
  EXPECT_GT(ellipsoid_ball, 0) << "no ellipsoid ever touched a clump ball";
}

// The pipeline of a sphere-only scene has no clump stage and no body field;
// a clump scene has both, the body sum last of the force phase.
TEST(ClumpDynamics, SphereScenePipelineIsUnchanged) {
  (void)clump_test_dir();
  auto scene = [](const std::string& shape) {
    std::ostringstream y;
    y << "domain: {min: [-0.001, -0.001, -0.001], max: [0.011, 0.011, 0.03]}\ngravity: [0, 0, -9.81]\nmaterials:\n"
      << material("grain", kRho, kE, kNu, 0.5, 0.5)
      << "particles:\n  - {name: a, material: grain, radius: 0.0006, count: 20, shape: " << shape
      << ", placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}}\n"
      << box_walls(0.01) << "time: {dt_rayleigh: 0.2, end: 0.001}\n";
    return from_yaml(y.str());
  };
  auto spheres = scene("{type: sphere}");
  const std::vector<std::string> expected = {
      "drift: verlet.kick_drift+rotation+force_start",
      "neighbor: neighbor.verlet_list(skin trigger)",
      "force: force.clear+torque+gravity(owned: in the drift)",
      "force: force.pair_contacts<hertz+tangential:mindlin+rolling:none+cohesion:none>",
      "force: force.walls<hertz+tangential:mindlin+rolling:none+cohesion:none>",
      "kick: verlet.kick+rotation"};
  EXPECT_EQ(spheres.pipeline.stage_names(), expected);
  EXPECT_FALSE(spheres.scene.particles.fields().has(sim::Field::Body));
  EXPECT_TRUE(spheres.scene.particles.body.empty());
  EXPECT_EQ(spheres.scene.bodies.size(), 0u);

  auto clumps = scene("{type: clump, file: " + dimer_file(0.0004, 0.0004) + "}");
  EXPECT_TRUE(clumps.scene.particles.fields().has(sim::Field::Body));
  EXPECT_EQ(clumps.scene.bodies.size(), 20u);
  EXPECT_EQ(clumps.scene.particles.n_owned(), 40u);
  const auto names = clumps.pipeline.stage_names();
  const std::vector<std::string> expected_clumps = {
      "drift: verlet.kick_drift+rotation(free particles)",
      "drift: clump.kick_drift(quaternion midpoint)+place_balls",
      "neighbor: neighbor.verlet_list(skin trigger)",
      "force: force.clear+torque+gravity(clump balls: 0)",
      "force: force.pair_contacts<hertz+tangential:mindlin+rolling:none+cohesion:none>",
      "force: force.walls<hertz+tangential:mindlin+rolling:none+cohesion:none>",
      "force: force.clump_sum(balls -> bodies)",
      "kick: verlet.kick+rotation(free particles)",
      "kick: clump.kick+ball_velocities"};
  EXPECT_EQ(names, expected_clumps);
}

// Mass and inertia scale with the set's radius (the bounding radius): s^3, s^5.
TEST(ClumpDynamics, MassAndInertiaScaleWithTheBoundingRadius) {
  auto make = [](double r) {
    std::ostringstream y;
    y.precision(17);
    y << "domain: {min: [-0.1, -0.1, -0.1], max: [0.1, 0.1, 0.1]}\nmaterials:\n"
      << material("grain", kRho, kE, kNu, 0.5, 0.0) << "particles:\n  - {name: a, material: grain, radius: " << r
      << ", count: 1, shape: {type: clump, file: " << dimer_file(0.5, 0.5)
      << "}, placement: {type: lattice, region: {min: [-0.05, -0.05, -0.05], max: [0.05, 0.05, 0.05]}}}\n"
      << "time: {dt_rayleigh: 0.2, end: 0.0001}\n";
    return from_yaml(y.str());
  };
  auto a = make(0.001), b = make(0.002);
  ASSERT_EQ(a.scene.bodies.size(), 1u);
  EXPECT_NEAR(b.scene.bodies.mass[0] / a.scene.bodies.mass[0], 8.0, 1e-12);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(b.scene.bodies.inertia[0][c] / a.scene.bodies.inertia[0][c], 32.0, 1e-11);
  // Bounding radius = the set's radius: balls of radius 2/3 r, centres r/3 from the centre of mass.
  const auto& p = a.scene.particles;
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(p.radius[i], 0.001 * 2 / 3, 1e-12);
    EXPECT_NEAR((p.x[i] - a.scene.bodies.x[0]).norm(), 0.001 / 3, 1e-12);
    EXPECT_EQ(p.mass[i], a.scene.bodies.mass[0]);  // m* of ball contacts uses the body's mass
  }
}

}  // namespace
}  // namespace grains::test
