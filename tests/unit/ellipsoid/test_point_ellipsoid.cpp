// Closest point on an ellipsoid and the sphere-ellipsoid contact: optimality
// conditions, the seed's closed-form quartic on the easy (planar) cases,
// global minimality against surface sampling, hard cases, spheres exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/ellipsoid/point_ellipsoid.hpp"
#include "tests/unit/ellipsoid/random_ellipsoids.hpp"

namespace grains::contact {
namespace {

using Eigen::Vector3d;
using test::Rng;

double level(const Vector3d& x, const Vector3d& e) {
  return (x.array() / e.array()).square().sum();
}

TEST(PointEllipsoid, SpheresAreExact) {
  Rng rng(30);
  for (int k = 0; k < 1000; ++k) {
    const double a = rng.log_uniform(1e-3, 1e3);
    const Vector3d y = rng.unit_vector() * a * rng.log_uniform(1e-3, 1e3);
    const ClosestPoint cp = closest_point_on_ellipsoid_body(y, Vector3d::Constant(a));
    EXPECT_NEAR(cp.signed_distance, y.norm() - a, 1e-15 * std::max(y.norm(), a));
    EXPECT_LT((cp.point - a * y.normalized()).norm(), 4e-16 * a * 4);
    EXPECT_LE(cp.iterations, 1);
  }
}

TEST(PointEllipsoid, OptimalityConditions) {
  // On the surface, and p - x along the surface normal, for aspect ratios up
  // to 1000, inside and outside.
  Rng rng(31);
  int max_it = 0;
  for (double ar : {1.5, 10.0, 100.0, 1000.0}) {
    for (int k = 0; k < 500; ++k) {
      const Vector3d e(rng.uniform(1, ar), 1, rng.uniform(1, ar));
      const Vector3d y = Vector3d(rng.normal() * e[0], rng.normal() * e[1], rng.normal() * e[2]) *
                         rng.log_uniform(0.01, 10);
      const ClosestPoint cp = closest_point_on_ellipsoid_body(y, e);
      max_it = std::max(max_it, cp.iterations);
      EXPECT_NEAR(level(cp.point, e), 1.0, 1e-14);
      const Vector3d d = y - cp.point;
      EXPECT_LT(d.cross(cp.normal).norm(), 1e-12 * (d.norm() + e.maxCoeff()));
      EXPECT_NEAR(std::abs(cp.signed_distance), d.norm(), 1e-12 * e.maxCoeff());
      EXPECT_EQ(cp.signed_distance < 0, level(y, e) < 1);
      if (cp.signed_distance > 0) {
        EXPECT_GT(d.dot(cp.normal), 0);
      }
    }
  }
  std::cout << "closest point: at most " << max_it << " Newton steps\n";
  EXPECT_LE(max_it, 30);
}

TEST(PointEllipsoid, SatisfiesTheSeedsQuartic) {
  // Seed 003, "Shortest distance from point to coplanar conic", exercise: for
  // the standard-form conic a00 + a11 x1^2 + a22 x2^2 = 0 and a point P(p1, p2)
  // the closest point's x1 is a root of P x^4 + Q x^3 + R x^2 + S x + T with
  //   P = a11 (a11 - a22)^2,            Q = 2 a11 a22 p1 (a11 - a22),
  //   R = a11 a22 (a11 p2^2 - 2 a00 + a22 p1^2) + a00 (a11^2 + a22^2),
  //   S = 2 a00 a22 p1 (a11 - a22),     T = a00 a22^2 p1^2.
  // A point in a principal plane of the ellipsoid has its closest point in
  // that plane when the plane's normal axis is not the shortest (otherwise an
  // inside point may be closer to the top or bottom), so the 3-D routine must
  // produce a root of this quartic.
  Rng rng(32);
  for (int k = 0; k < 500; ++k) {
    Vector3d e(rng.uniform(0.5, 5), rng.uniform(0.5, 5), 0);
    e[2] = rng.uniform(e.maxCoeff(), 6);
    const double p1 = rng.uniform(-8, 8), p2 = rng.uniform(-8, 8);
    const ClosestPoint cp = closest_point_on_ellipsoid_body(Vector3d(p1, p2, 0), e);
    EXPECT_EQ(cp.point[2], 0.0);
    const long double a00 = -1, a11 = 1 / (e[0] * (long double)e[0]), a22 = 1 / (e[1] * (long double)e[1]);
    const long double P = a11 * (a11 - a22) * (a11 - a22), Q = 2 * a11 * a22 * p1 * (a11 - a22),
                      R = a11 * a22 * (a11 * p2 * p2 - 2 * a00 + a22 * p1 * p1) + a00 * (a11 * a11 + a22 * a22),
                      S = 2 * a00 * a22 * p1 * (a11 - a22), T = a00 * a22 * a22 * p1 * p1;
    const long double x = cp.point[0];
    const long double terms[] = {P * x * x * x * x, Q * x * x * x, R * x * x, S * x, T};
    long double sum = 0, mag = 0;
    for (long double t : terms) {
      sum += t;
      mag += std::abs(t);
    }
    EXPECT_LT(std::abs(sum), 1e-13 * mag) << "e = " << e.transpose() << ", P = " << p1 << ", " << p2;
  }
}

TEST(PointEllipsoid, GloballyClosestAgainstSampling) {
  Rng rng(33);
  for (int k = 0; k < 60; ++k) {
    const Vector3d e(rng.uniform(0.3, 4), rng.uniform(0.3, 4), rng.uniform(0.3, 4));
    const Vector3d y = rng.unit_vector() * rng.uniform(0, 6);
    const ClosestPoint cp = closest_point_on_ellipsoid_body(y, e);
    double best = INFINITY;
    const int m = 200;
    for (int i = 0; i <= m; ++i) {
      const double th = std::numbers::pi * i / m;
      for (int j = 0; j < 2 * m; ++j) {
        const double ph = std::numbers::pi * j / m;
        const Vector3d x(e[0] * std::sin(th) * std::cos(ph), e[1] * std::sin(th) * std::sin(ph), e[2] * std::cos(th));
        best = std::min(best, (x - y).norm());
      }
    }
    EXPECT_LE(std::abs(cp.signed_distance), best + 1e-12);
    EXPECT_GE(std::abs(cp.signed_distance), best - 0.05 * e.maxCoeff());  // sampling resolution
  }
}

TEST(PointEllipsoid, HardCasesInside) {
  const Vector3d e(3, 2, 1);
  // Centre: the ends of the shortest axis.
  ClosestPoint cp = closest_point_on_ellipsoid_body(Vector3d::Zero(), e);
  EXPECT_DOUBLE_EQ(cp.signed_distance, -1.0);
  EXPECT_NEAR(std::abs(cp.point[2]), 1.0, 1e-15);
  // On the plane z = 0 near the centre: closest point still above/below.
  // Candidate x_i = e_i^2 y_i / (e_i^2 - e_z^2): (9*0.5/8, 4*0.3/3) = (0.5625, 0.4).
  cp = closest_point_on_ellipsoid_body(Vector3d(0.5, 0.3, 0), e);
  EXPECT_NEAR(cp.point[0], 0.5625, 1e-15);
  EXPECT_NEAR(cp.point[1], 0.4, 1e-15);
  EXPECT_NEAR(level(cp.point, e), 1.0, 1e-15);
  const double d_expected = std::sqrt(0.0625 * 0.0625 + 0.1 * 0.1 + cp.point[2] * cp.point[2]);
  EXPECT_NEAR(cp.signed_distance, -d_expected, 1e-15);
  // Far along x on the plane z = 0 inside: the closest point lies in the plane.
  cp = closest_point_on_ellipsoid_body(Vector3d(2.9, 0, 0), e);
  EXPECT_NEAR(cp.signed_distance, -0.1, 1e-15);
  EXPECT_EQ(cp.point[2], 0.0);
  // Spheroid with two equal short axes, point on its axis.
  cp = closest_point_on_ellipsoid_body(Vector3d(0.2, 0, 0), Vector3d(3, 1, 1));
  // x = (9 * 0.2 / 8, sqrt(1 - 0.075^2), 0): distance^2 = 0.025^2 + 1 - 0.075^2.
  EXPECT_NEAR(cp.signed_distance, -std::sqrt(0.995), 1e-15);
  EXPECT_NEAR(level(cp.point, Vector3d(3, 1, 1)), 1.0, 1e-15);
}

TEST(SphereEllipsoid, ContactGeometry) {
  Rng rng(34);
  for (int k = 0; k < 300; ++k) {
    Ellipsoid body;
    body.centre = Vector3d(rng.normal(), rng.normal(), rng.normal());
    body.semi_axes = Vector3d(rng.uniform(0.5, 3), rng.uniform(0.5, 3), rng.uniform(0.5, 3));
    body.orientation = rng.rotation();
    const double radius = rng.uniform(0.1, 2);
    const Vector3d c = body.centre + rng.unit_vector() * rng.uniform(0.5, 5);
    bool touching = false;
    const ContactGeometry g = sphere_ellipsoid_contact(c, radius, body, &touching);
    const ClosestPoint cp = closest_point_on_ellipsoid(c, body);
    EXPECT_EQ(touching, radius > cp.signed_distance);
    EXPECT_NEAR(g.overlap, radius - cp.signed_distance, 1e-14);
    EXPECT_NEAR(g.normal.norm(), 1.0, 1e-15);
    EXPECT_GT(g.radius, 0.0);
    EXPECT_LT(g.radius, radius);  // R* < min(R_sphere, R_ellipsoid)
    if (cp.signed_distance > 0) {
      EXPECT_LT((c - cp.point - cp.signed_distance * g.normal).norm(), 1e-12);
    }
  }
  // A sphere against a spherical "ellipsoid" is the sphere-sphere contact.
  Ellipsoid ball;
  ball.semi_axes = Vector3d::Constant(2.0);
  ball.orientation = rng.rotation();
  const ContactGeometry g = sphere_ellipsoid_contact(Vector3d(0, 0, 2.5), 1.0, ball);
  EXPECT_NEAR(g.overlap, 0.5, 1e-15);
  EXPECT_LT((g.normal - Vector3d(0, 0, 1)).norm(), 1e-15);
  EXPECT_LT((g.point - Vector3d(0, 0, 1.75)).norm(), 1e-15);
  EXPECT_NEAR(g.radius, 2.0 / 3.0, 1e-15);
}

}  // namespace
}  // namespace grains::contact
