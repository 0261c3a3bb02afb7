// Ellipsoid DEM: the quaternion rigid-body integrator and the PW85 contacts
// inside real scenes.
#include <gtest/gtest.h>

#include <cstdio>

#include "contact/ellipsoid/ellipsoid_walls.hpp"
#include "sim/integrate/rigid_body.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

const std::string kMaterial =
    "materials:\n  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}\n";

TEST(RigidBody, TorqueFreeAsymmetricTopOverAMillionSteps) {
  // A tumbling asymmetric body: |q| = 1 to rounding, L exactly conserved,
  // rotational energy bounded (symplectic-like midpoint rotation).
  sim::ParticleStore p;
  p.configure(sim::FieldSet(sim::Field::AngularVelocity) | sim::Field::Torque | sim::Field::Inertia |
                  sim::Field::Orientation | sim::Field::AngularMomentum | sim::Field::SemiAxes | sim::Field::ShapeForm,
              0);
  p.add(0, sim::Vec3::Zero(), sim::Vec3::Zero(), 1.0, 1.0, 0, sim::kEllipsoid);
  p.semi_axes[0] = sim::Vec3(1.0, 0.6, 0.3);
  p.inertia[0] = sim::Vec3(1.0, 2.0, 3.0);
  p.angular_momentum[0] = sim::Vec3(0.3, 2.0, 0.1);  // near the unstable middle axis: tumbling
  p.omega[0] = sim::angular_velocity(p.orientation[0], p.inertia[0], p.angular_momentum[0]);
  sim::Scene s;
  s.particles = p;
  s.clock.dt = 1e-3;
  sim::RigidBodyDrift drift;
  sim::RigidBodyKick kick;
  auto energy = [&] { return 0.5 * s.particles.omega[0].dot(s.particles.angular_momentum[0]); };
  const double e0 = energy();
  const sim::Vec3 L0 = s.particles.angular_momentum[0];
  double worst_norm = 0, worst_e = 0;
  for (int k = 0; k < 1000000; ++k) {
    drift.run(s);
    kick.run(s);
    if (k % 1000 == 0) {
      worst_norm = std::max(worst_norm, std::abs(s.particles.orientation[0].norm() - 1.0));
      worst_e = std::max(worst_e, std::abs(energy() - e0) / e0);
    }
  }
  std::printf("torque-free top, 1e6 steps of |w| dt ~ 2e-3: worst | |q| - 1 | = %.2e, worst relative energy error = %.3e\n",
              worst_norm, worst_e);
  EXPECT_LT(worst_norm, 1e-14);
  EXPECT_EQ(s.particles.angular_momentum[0], L0);
  EXPECT_LT(worst_e, 1e-3);
  // The rotation matrix built from q stays orthonormal.
  const Eigen::Matrix3d R = s.particles.orientation[0].toRotationMatrix();
  EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-14);
}

std::string dropped_spheroid(const std::string& material) {
  return "domain: {min: [-0.01, -0.01, -0.001], max: [0.01, 0.01, 0.02]}\n"
         "gravity: [0, 0, -9.81]\n" + material +
         "particles:\n  - {material: m, radius: 0.001, count: 1, shape: {type: ellipsoid, aspect_ratio: 2, "
         "orientation: [0.92388, 0.0, 0.38268, 0.0]}, placement: {type: lattice, region: {min: [-0.0016, -0.0016, 0.003], "
         "max: [0.0016, 0.0016, 0.0063]}}}\n"
         "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}\n";
}

double mechanical_energy(const sim::Scene& s) {
  const auto& p = s.particles;
  const Eigen::Matrix3d R = p.orientation[0].toRotationMatrix();
  const sim::Vec3 wb = R.transpose() * p.omega[0];
  return 0.5 * p.mass[0] * p.v[0].squaredNorm() + 0.5 * wb.dot(p.inertia[0].cwiseProduct(wb)) -
         p.mass[0] * s.gravity.dot(p.x[0]);
}

TEST(EllipsoidDem, ElasticFrictionlessBouncesConserveEnergy) {
  // e = 1, no friction: a tilted spheroid bounces and spins; between contacts
  // its kinetic + potential energy must return to the initial value (the
  // contact torque is conservative: lever arm to the support point).
  auto s = from_yaml(dropped_spheroid("materials:\n  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, "
                                      "restitution: 1.0, friction: 0}\n") +
                     "time: {dt_rayleigh: 0.05, end: 0.3}\n");
  s.pipeline.initialize(s.scene);
  const double e0 = mechanical_energy(s.scene);
  double worst = 0;
  int flights = 0;
  bool in_contact = false;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    // In contact when the force differs from gravity alone.
    const double mg = s.scene.particles.mass[0] * 9.81;
    const bool c = (s.scene.particles.f[0] - sim::Vec3(0, 0, -mg)).norm() > 1e-9 * mg;
    if (!c) worst = std::max(worst, std::abs(mechanical_energy(s.scene) - e0) / e0);
    if (in_contact && !c) ++flights;
    in_contact = c;
  }
  EXPECT_GE(flights, 2);
  EXPECT_LT(worst, 5e-3);
}

TEST(EllipsoidDem, ProlateSpheroidComesToRestLyingFlat) {
  // Dropped tilted onto a floor, a 2:1 prolate spheroid ends on its side:
  // long axis horizontal, centre at the short semi-axis. Without rolling
  // resistance a spheroid rocks for a long time (rocking barely changes the
  // overlap, so normal damping hardly acts); with it, it settles.
  auto s = from_yaml(dropped_spheroid(kMaterial) + "time: {dt_rayleigh: 0.2, end: 1.0}\n",
                     {"materials.0.rolling_friction=0.1"});
  s.pipeline.initialize(s.scene);
  while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
  const auto& p = s.scene.particles;
  const double b = 0.001 / std::cbrt(2.0);
  const sim::Vec3 long_axis = p.orientation[0].toRotationMatrix().col(0);
  EXPECT_LT(std::abs(long_axis.z()), 0.06) << long_axis.transpose();
  EXPECT_NEAR(p.x[0].z() / b, 1.0, 0.01);
  EXPECT_LT(p.v[0].norm(), 1e-3);
}

TEST(EllipsoidDem, AlignedSpheroidsHeadOnAchieveTheRestitution) {
  // Tip-to-tip along the long axes: a central impact, so the calibrated
  // damping gives the target restitution whatever the curvature.
  std::ostringstream y;
  y << "domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}\n" << kMaterial << "particles:\n";
  const double a = 0.001 * std::cbrt(4.0);
  for (int side : {-1, 1}) {
    const double cx = side * (a * 1.02);
    y << "  - {name: s" << (side + 1) << ", material: m, radius: 0.001, count: 1, velocity: [" << -side * 0.5
      << ", 0, 0], shape: {type: ellipsoid, aspect_ratio: 2, orientation: [1, 0, 0, 0]}, placement: {type: lattice, "
      << "region: {min: [" << cx - a << ", " << -a << ", " << -a << "], max: [" << cx + 1.4 * a << ", " << 1.4 * a
      << ", " << 1.4 * a << "]}}}\n";
  }
  y << "contact: {tangential: none}\ntime: {dt_rayleigh: 0.05, end: 0.004}\n";
  auto s = from_yaml(y.str());
  s.pipeline.initialize(s.scene);
  while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
  const auto& p = s.scene.particles;
  const double vrel = p.v[index_of(p, 1)].x() - p.v[index_of(p, 0)].x();
  EXPECT_NEAR(vrel / 1.0, 0.5, 0.005);
}

TEST(EllipsoidDem, SpheroidsPouredAroundAPostStayOutOfIt) {
  // 40 prolate spheroids (aspect ratio 2) fall around a vertical post (a
  // cylinder wall with inside: false) onto a floor. Many touch the post;
  // none may sink into it by more than a few percent of its short
  // semi-axis, and every state stays finite.
  std::string yaml =
      "domain: {min: [0, 0, 0], max: [0.012, 0.012, 0.03]}\ngravity: [0, 0, -9.81]\n" + kMaterial + "particles:\n";
  // Two columns on either side of the post, thrown towards it.
  const std::pair<const char*, const char*> sides[] = {
      {"{min: [0.0008, 0.004, 0.001], max: [0.0036, 0.008, 0.028]}", "[0.3, 0, 0]"},
      {"{min: [0.0084, 0.004, 0.001], max: [0.0112, 0.008, 0.028]}", "[-0.3, 0, 0]"}};
  for (const auto& [region, velocity] : sides)
    yaml += std::string("  - {material: m, radius: 0.0005, count: 20, velocity: ") + velocity +
            ", shape: {type: ellipsoid, aspect_ratio: 2}, placement: {type: random_fill, seed: 3, region: " + region +
            "}}\n";
  yaml += "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}\n"
          "  - {type: plane, point: [0, 0, 0], normal: [1, 0, 0], material: m}\n"
          "  - {type: plane, point: [0.012, 0, 0], normal: [-1, 0, 0], material: m}\n"
          "  - {type: plane, point: [0, 0, 0], normal: [0, 1, 0], material: m}\n"
          "  - {type: plane, point: [0, 0.012, 0], normal: [0, -1, 0], material: m}\n"
          "  - {type: cylinder, name: post, base: [0.006, 0.006, 0], radius: 0.002, height: 0.03, inside: false, "
          "material: m}\n"
          "time: {dt_rayleigh: 0.2, end: 0.12}\n";
  auto s = from_yaml(yaml);
  s.pipeline.initialize(s.scene);
  const auto& p = s.scene.particles;
  const double b = 0.0005 / std::cbrt(2.0);  // short semi-axis
  contact::CylinderSurface post;
  post.base = sim::Vec3(0.006, 0.006, 0);
  post.radius = 0.002;
  post.inside = false;
  double worst = 0;
  int touching_steps = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    for (std::size_t i = 0; i < p.n_owned(); ++i) {
      ASSERT_TRUE(p.x[i].allFinite() && p.v[i].allFinite());
      bool touching = false;
      const auto g = contact::ellipsoid_cylinder_contact({p.x[i], p.semi_axes[i], p.orientation[i]}, post, &touching);
      worst = std::max(worst, g.overlap);
      touching_steps += touching;
    }
  }
  EXPECT_EQ(p.n_owned(), 40u);
  EXPECT_GT(touching_steps, 100);
  EXPECT_LT(worst / b, 0.05);
  // The post holds the grains off its axis: every centre outside it.
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    EXPECT_GT((p.x[i] - post.base).head<2>().norm(), post.radius + 0.9 * b);
}

TEST(EllipsoidDem, PipelineHasShapeStagesAndFields) {
  const std::string yaml = "domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}\n" + kMaterial +
                           "particles:\n  - {material: m, radius: 0.0005, count: 20, shape: {type: ellipsoid, aspect_ratio: 1.5}, "
                           "placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}}\n"
                           "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}\n"
                           "time: {dt_rayleigh: 0.2, end: 0.001}\n";
  auto s = from_yaml(yaml);
  const auto names = s.pipeline.stage_names();
  EXPECT_EQ(names[0], "drift: rigid_body.kick_drift(quaternion midpoint)");
  EXPECT_NE(std::find(names.begin(), names.end(),
                      "force: force.pair_contacts[sphere|ellipsoid]<hertz+tangential:mindlin+rolling:none+cohesion:none>"),
            names.end());
  const auto f = s.scene.particles.field_names();
  for (const char* want : {"orientation", "angular_momentum", "semi_axes", "shape_form"})
    EXPECT_NE(std::find(f.begin(), f.end(), want), f.end()) << want;
  EXPECT_EQ(s.scene.neighbors.history_size(), 4);  // Mindlin 3 + PW85 lambda
}

}  // namespace
}  // namespace grains::test
