// Ellipsoid against a plane, inside a cylinder and outside one (a post):
// closed forms for spheres and aligned spheroids, and brute-force surface sampling for general poses.
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

TEST(EllipsoidPost, SphereOutsideACylinder) {
  // A post of radius 2 and a unit sphere at 2.9 from its axis: overlap 0.1,
  // pushed radially outwards, R* of a sphere on a cylinder 1/sqrt((1+1/2) 1).
  CylinderWall w;
  w.radius = 2;
  w.inside = false;
  Ellipsoid ball;
  ball.semi_axes = Vector3d::Constant(1.0);
  ball.orientation = Quat(Eigen::AngleAxisd(0.4, Vector3d(1, 1, 0).normalized()));
  ball.centre = Vector3d(0.6, -0.8, 0) * 2.9 + Vector3d(0, 0, -3);
  bool touching = false;
  const ContactGeometry g = ellipsoid_cylinder_contact(ball, w, &touching);
  EXPECT_TRUE(touching);
  EXPECT_NEAR(g.overlap, 0.1, 1e-14);
  EXPECT_LT((g.normal - Vector3d(0.6, -0.8, 0)).norm(), 1e-14);
  EXPECT_LT((g.point - (Vector3d(0.6, -0.8, 0) * 1.95 + Vector3d(0, 0, -3))).norm(), 1e-14);
  EXPECT_NEAR(g.radius, 1 / std::sqrt((1 + 0.5) * 1), 1e-14);
  ball.centre = Vector3d(0.6, -0.8, 0) * 3.1;
  ellipsoid_cylinder_contact(ball, w, &touching);
  EXPECT_FALSE(touching);
}

TEST(EllipsoidPost, LyingSpheroidTipAgainstThePost) {
  // Prolate (a, b, b) pointing at the axis: overlap = R_c + a - offset,
  // principal radii b^2/a at the tip, the post convex around it.
  CylinderWall w;
  w.radius = 1;
  w.inside = false;
  Ellipsoid s;
  s.semi_axes = Vector3d(2, 0.5, 0.5);
  s.centre = Vector3d(-2.9, 0, 0);
  const ContactGeometry g = ellipsoid_cylinder_contact(s, w);
  EXPECT_NEAR(g.overlap, 0.1, 1e-14);
  EXPECT_LT((g.normal - Vector3d(-1, 0, 0)).norm(), 1e-14);
  const double k = 2 / 0.25;  // a / b^2
  EXPECT_NEAR(g.radius, 1 / std::sqrt(k * (k + 1)), 1e-13);
}

TEST(EllipsoidPost, ClosestPointAgainstSampling) {
  // General poses: the overlap is R_c minus the sampled distance from the
  // axis to the body (when the axis misses the body), the normal is radial
  // and normal to the axis; when the axis pierces the body the overlap
  // exceeds R_c and stays finite.
  Rng rng(42);
  int pierced = 0;
  for (int k = 0; k < 80; ++k) {
    CylinderWall w;
    w.axis = rng.unit_vector();
    w.axis_point = Vector3d(rng.normal(), rng.normal(), rng.normal());
    w.radius = rng.uniform(0.1, 2);
    w.inside = false;
    Ellipsoid b;
    b.semi_axes = Vector3d(rng.uniform(0.2, 3), rng.uniform(0.2, 3), rng.uniform(0.2, 3));
    b.orientation = rng.rotation();
    Vector3d off = rng.unit_vector();
    off -= off.dot(w.axis) * w.axis;
    off.normalize();
    b.centre = w.axis_point + (k % 8 == 0 ? 0.0 : rng.uniform(0, 5)) * off + rng.normal() * w.axis;
    const ContactGeometry g = ellipsoid_cylinder_contact(b, w);
    ASSERT_TRUE(std::isfinite(g.overlap) && std::isfinite(g.radius) && g.normal.allFinite());
    EXPECT_NEAR(g.normal.dot(w.axis), 0.0, 1e-13);
    EXPECT_NEAR(g.normal.norm(), 1.0, 1e-14);
    EXPECT_GT(g.radius, 0.0);
    double near = INFINITY;
    for_surface_samples(b, 150, [&](const Vector3d& x) {
      const Vector3d rel = x - w.axis_point;
      near = std::min(near, (rel - rel.dot(w.axis) * w.axis).norm());
    });
    // Is the axis through the body? (Its closest approach to the centre, in
    // the body frame, inside the unit ball.)
    const Mat3 R = b.orientation.toRotationMatrix();
    const Vector3d rel = b.centre - w.axis_point;
    const Vector3d foot = w.axis_point + rel.dot(w.axis) * w.axis;
    // Minimise the body-frame norm along the axis line: a 1D quadratic.
    const Vector3d p0 = (R.transpose() * (foot - b.centre)).cwiseQuotient(b.semi_axes);
    const Vector3d dv = (R.transpose() * w.axis).cwiseQuotient(b.semi_axes);
    const double tmin = -p0.dot(dv) / dv.squaredNorm();
    if ((p0 + tmin * dv).norm() < 1.0) {
      ++pierced;
      EXPECT_GT(g.overlap, w.radius);
      continue;
    }
    // Samples are never closer to the axis than the body is.
    EXPECT_GE(g.overlap, w.radius - near - 1e-12);
    EXPECT_LE(g.overlap, w.radius - near + 1e-3 * b.semi_axes.maxCoeff());
  }
  EXPECT_GE(pierced, 10);
}

}  // namespace
}  // namespace grains::contact
