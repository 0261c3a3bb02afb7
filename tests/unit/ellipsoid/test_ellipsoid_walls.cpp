// Ellipsoid against a plane and inside a cylinder: closed forms for spheres
// and aligned spheroids, and brute-force surface sampling for general poses.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/ellipsoid/ellipsoid_walls.hpp"
#include "tests/unit/ellipsoid/random_ellipsoids.hpp"

namespace grains::contact {
namespace {

using Eigen::Vector3d;
using test::Rng;

// Surface points of the body on an (m x 2m) angle grid.
template <class F>
void for_surface_samples(const Ellipsoid& b, int m, F f) {
  const Mat3 R = b.orientation.toRotationMatrix();
  for (int i = 0; i <= m; ++i) {
    const double th = std::numbers::pi * i / m;
    for (int j = 0; j < 2 * m; ++j) {
      const double ph = std::numbers::pi * j / m;
      const Vector3d x(b.semi_axes[0] * std::sin(th) * std::cos(ph), b.semi_axes[1] * std::sin(th) * std::sin(ph),
                       b.semi_axes[2] * std::cos(th));
      f(b.centre + R * x);
    }
  }
}

TEST(EllipsoidPlane, SphereAndStandingSpheroid) {
  Ellipsoid ball;
  ball.semi_axes = Vector3d::Constant(1.5);
  ball.centre = Vector3d(0.3, -2, 1.2);
  ball.orientation = Quat(Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()));
  bool touching = false;
  ContactGeometry g = ellipsoid_plane_contact(ball, PlaneWall{}, &touching);
  EXPECT_TRUE(touching);
  EXPECT_NEAR(g.overlap, 0.3, 1e-15);
  EXPECT_LT((g.normal - Vector3d(0, 0, 1)).norm(), 1e-15);
  EXPECT_LT((g.point - Vector3d(0.3, -2, -0.15)).norm(), 1e-15);
  EXPECT_NEAR(g.radius, 1.5, 1e-14);
  // Prolate spheroid standing on its tip: principal radii b^2/a at the tip.
  Ellipsoid s;
  s.semi_axes = Vector3d(3, 1, 1);
  s.orientation = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d(0, 1, 0)));  // x -> -z
  s.centre = Vector3d(0, 0, 2.9);
  g = ellipsoid_plane_contact(s, PlaneWall{}, &touching);
  EXPECT_TRUE(touching);
  EXPECT_NEAR(g.overlap, 0.1, 1e-14);
  EXPECT_NEAR(g.radius, 1.0 / 3.0, 1e-14);
  // Lying on its flank: radii b and a^2/b, R* = sqrt(b * a^2/b) = a.
  s.orientation = Quat::Identity();
  s.centre = Vector3d(0, 0, 1.05);
  g = ellipsoid_plane_contact(s, PlaneWall{}, &touching);
  EXPECT_FALSE(touching);
  EXPECT_NEAR(g.overlap, -0.05, 1e-15);
  EXPECT_NEAR(g.radius, 3.0, 1e-14);
}

TEST(EllipsoidPlane, DeepestPointAgainstSampling) {
  Rng rng(40);
  for (int k = 0; k < 50; ++k) {
    Ellipsoid b;
    b.semi_axes = Vector3d(rng.uniform(0.2, 3), rng.uniform(0.2, 3), rng.uniform(0.2, 3));
    b.orientation = rng.rotation();
    b.centre = rng.unit_vector() * 2;
    PlaneWall w;
    w.normal = rng.unit_vector();
    w.point = Vector3d(rng.normal(), rng.normal(), rng.normal());
    const ContactGeometry g = ellipsoid_plane_contact(b, w);
    double deepest = -INFINITY;
    for_surface_samples(b, 150, [&](const Vector3d& x) { deepest = std::max(deepest, -(x - w.point).dot(w.normal)); });
    EXPECT_GE(g.overlap, deepest - 1e-12);
    EXPECT_LE(g.overlap, deepest + 1e-3 * b.semi_axes.maxCoeff());
    // The contact point lies on the plane shifted by half the overlap.
    EXPECT_NEAR((g.point - w.point).dot(w.normal), -0.5 * g.overlap, 1e-12);
  }
}

TEST(EllipsoidCylinder, SphereInsideACylinder) {
  CylinderWall w;
  w.radius = 5;
  Ellipsoid ball;
  ball.semi_axes = Vector3d::Constant(1.0);
  ball.centre = Vector3d(0.6, 0.8, 0) * 4.2 + Vector3d(0, 0, 0.7);
  bool touching = false;
  const ContactGeometry g = ellipsoid_cylinder_contact(ball, w, &touching);
  EXPECT_TRUE(touching);
  EXPECT_NEAR(g.overlap, 0.2, 1e-14);
  EXPECT_LT((g.normal + Vector3d(0.6, 0.8, 0)).norm(), 1e-14);
  EXPECT_LT((g.point - (Vector3d(0.6, 0.8, 0) * 5.1 + Vector3d(0, 0, 0.7))).norm(), 1e-14);
  // Relative curvatures 1/a - 1/R_c around, 1/a along the axis.
  EXPECT_NEAR(g.radius, 1 / std::sqrt((1 - 0.2) * 1), 1e-14);
  // Outside the wall's axial extent: no contact.
  w.z_min = 1.0;
  ellipsoid_cylinder_contact(ball, w, &touching);
  EXPECT_FALSE(touching);
}

TEST(EllipsoidCylinder, FarthestPointAgainstSampling) {
  Rng rng(41);
  for (int k = 0; k < 60; ++k) {
    CylinderWall w;
    w.axis = rng.unit_vector();
    w.axis_point = Vector3d(rng.normal(), rng.normal(), rng.normal());
    w.radius = 6;
    Ellipsoid b;
    b.semi_axes = Vector3d(rng.uniform(0.2, 3), rng.uniform(0.2, 3), rng.uniform(0.2, 3));
    b.orientation = rng.rotation();
    Vector3d off = rng.unit_vector();
    off -= off.dot(w.axis) * w.axis;
    // Half the cases with the centre exactly on the axis (the hard case).
    b.centre = w.axis_point + (k % 2 ? rng.uniform(0, 3) : 0.0) * off + rng.normal() * w.axis;
    const ContactGeometry g = ellipsoid_cylinder_contact(b, w);
    double far = 0;
    for_surface_samples(b, 150, [&](const Vector3d& x) {
      const Vector3d rel = x - w.axis_point;
      far = std::max(far, (rel - rel.dot(w.axis) * w.axis).norm());
    });
    EXPECT_GE(g.overlap, far - w.radius - 1e-12);
    EXPECT_LE(g.overlap, far - w.radius + 1e-3 * b.semi_axes.maxCoeff());
    EXPECT_NEAR(g.normal.dot(w.axis), 0.0, 1e-14);
    EXPECT_GT(g.radius, 0.0);
    EXPECT_TRUE(std::isfinite(g.radius));
  }
}

TEST(EllipsoidCylinder, LyingSpheroidTipTouchesTheWall) {
  // Prolate (a, b, b) with its axis radial: the tip is the farthest point,
  // overlap = offset + a - R_c; principal radii at the tip are b^2/a, and the
  // wall (radius R_c) is concave around the circumference.
  CylinderWall w;
  w.radius = 4;
  Ellipsoid s;
  s.semi_axes = Vector3d(2, 0.5, 0.5);
  s.centre = Vector3d(2.1, 0, 0);
  const ContactGeometry g = ellipsoid_cylinder_contact(s, w);
  EXPECT_NEAR(g.overlap, 0.1, 1e-14);
  const double k = 2 / 0.25;  // a / b^2
  EXPECT_NEAR(g.radius, 1 / std::sqrt(k * (k - 0.25)), 1e-13);
}

}  // namespace
}  // namespace grains::contact
