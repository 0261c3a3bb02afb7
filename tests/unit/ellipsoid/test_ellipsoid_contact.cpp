// Ellipsoid-ellipsoid contact geometry from PW85: reduces to the sphere
// result, is symmetric under exchange, the overlap is the distance that makes
// the bodies tangent, and R* matches analytic principal curvatures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "contact/ellipsoid/ellipsoid_contact.hpp"
#include "contact/ellipsoid/surface_curvature.hpp"
#include "tests/unit/ellipsoid/random_ellipsoids.hpp"

namespace grains::contact {
namespace {

using Eigen::Vector3d;
using test::Rng;

TEST(EllipsoidContact, SpheresGiveTheSphereResult) {
  Rng rng(20);
  for (int k = 0; k < 500; ++k) {
    const double a1 = rng.log_uniform(0.01, 10), a2 = rng.log_uniform(0.01, 10);
    Ellipsoid i, j;
    i.centre = Vector3d(rng.normal(), rng.normal(), rng.normal());
    i.semi_axes = Vector3d::Constant(a1);
    j.semi_axes = Vector3d::Constant(a2);
    i.orientation = rng.rotation();
    j.orientation = rng.rotation();
    const Vector3d u = rng.unit_vector();
    const double dist = (a1 + a2) * rng.uniform(0.5, 1.5);
    j.centre = i.centre + dist * u;
    const EllipsoidPairContact c = ellipsoid_contact(i, j);
    if (dist >= a1 + a2) {
      EXPECT_FALSE(c.touching);
      continue;
    }
    ASSERT_TRUE(c.touching);
    const double tol = 1e-14 * (a1 + a2);
    EXPECT_NEAR(c.geometry.overlap, a1 + a2 - dist, tol);
    EXPECT_LT((c.geometry.normal + u).norm(), 1e-14);  // from j towards i
    const Vector3d expected_point = i.centre + (a1 - 0.5 * (a1 + a2 - dist)) * u;
    EXPECT_LT((c.geometry.point - expected_point).norm(), tol);
    EXPECT_NEAR(c.geometry.radius, a1 * a2 / (a1 + a2), 1e-13 * a1 * a2 / (a1 + a2));
  }
}

TEST(EllipsoidContact, ExchangeFlipsTheNormalOnly) {
  Rng rng(21);
  for (int k = 0; k < 300; ++k) {
    Ellipsoid i, j;
    i.semi_axes = Vector3d(rng.uniform(1, 4), rng.uniform(0.5, 2), rng.uniform(0.3, 1));
    j.semi_axes = Vector3d(rng.uniform(1, 4), rng.uniform(0.5, 2), rng.uniform(0.3, 1));
    i.orientation = rng.rotation();
    j.orientation = rng.rotation();
    j.centre = rng.unit_vector() * rng.uniform(0.5, 3);
    const EllipsoidPairContact a = ellipsoid_contact(i, j), b = ellipsoid_contact(j, i);
    ASSERT_EQ(a.touching, b.touching);
    if (!a.touching) continue;
    EXPECT_LT((a.geometry.normal + b.geometry.normal).norm(), 1e-12);
    EXPECT_NEAR(a.geometry.overlap, b.geometry.overlap, 1e-12);
    EXPECT_LT((a.geometry.point - b.geometry.point).norm(), 1e-12);
    EXPECT_NEAR(a.geometry.radius, b.geometry.radius, 1e-12 * a.geometry.radius);
    EXPECT_NEAR(a.pw85.lambda, 1 - b.pw85.lambda, 1e-12);
  }
}

TEST(EllipsoidContact, OverlapIsTheSeparationToTangency) {
  // Moving j by `overlap` along -normal (away from i) must leave the pair
  // tangent up to second order in the overlap: |mu - 1| = O((overlap/size)^2).
  Rng rng(22);
  int n = 0;
  for (int k = 0; k < 400; ++k) {
    Ellipsoid i, j;
    i.semi_axes = Vector3d(rng.uniform(1, 3), rng.uniform(0.5, 1.5), rng.uniform(0.4, 1));
    j.semi_axes = Vector3d(rng.uniform(1, 3), rng.uniform(0.5, 1.5), rng.uniform(0.4, 1));
    i.orientation = rng.rotation();
    j.orientation = rng.rotation();
    j.centre = rng.unit_vector() * 2.5;
    // Bring the pair to tangency, then push in by a small depth.
    const double mu = std::sqrt(pw85_contact(j.centre - i.centre, i.form(), j.form()).mu2);
    const double depth = rng.log_uniform(1e-6, 1e-2);
    j.centre *= (1.0 / mu) * (1.0 - depth);
    const EllipsoidPairContact c = ellipsoid_contact(i, j);
    ASSERT_TRUE(c.touching);
    ++n;
    Ellipsoid moved = j;
    moved.centre -= c.geometry.overlap * c.geometry.normal;
    const double mu_after = std::sqrt(pw85_contact(moved.centre - i.centre, i.form(), moved.form()).mu2);
    const double rel_overlap = c.geometry.overlap / 0.4;  // smallest semi-axis
    EXPECT_LT(std::abs(mu_after - 1.0), 10 * rel_overlap * rel_overlap + 1e-14)
        << "overlap " << c.geometry.overlap;
    // And the overlap is consistent with the support-function identity.
    const double rn = (j.centre - i.centre).dot(-c.geometry.normal);
    EXPECT_NEAR(c.geometry.overlap, (1 / std::sqrt(c.pw85.mu2) - 1) * rn, 1e-12);
  }
  EXPECT_EQ(n, 400);
}

TEST(EllipsoidContact, HertzRadiusFromPrincipalCurvatures) {
  // Prolate spheroids (a, b, b) tip to tip: each tip has both principal radii
  // b^2/a, so R* = (b1^2/a1)(b2^2/a2) / (b1^2/a1 + b2^2/a2).
  for (double ar : {1.0, 2.0, 5.0, 50.0}) {
    Ellipsoid i, j;
    i.semi_axes = Vector3d(ar, 1, 1);
    j.semi_axes = Vector3d(2 * ar, 1.5, 1.5);
    j.centre = Vector3d(3 * ar * 0.999, 0, 0);
    const EllipsoidPairContact c = ellipsoid_contact(i, j);
    ASSERT_TRUE(c.touching);
    const double r1 = 1.0 / ar, r2 = 1.5 * 1.5 / (2 * ar);
    EXPECT_NEAR(c.geometry.radius, r1 * r2 / (r1 + r2), 1e-12 * r1);
    // Side by side (r along y): at the flank the principal radii are b (around
    // the axis) and a^2/b (along it): R*^2 = 1/det(K1 + K2), K diagonal.
    j.centre = Vector3d(0, 2.5 * 0.999, 0);
    const EllipsoidPairContact s = ellipsoid_contact(i, j);
    ASSERT_TRUE(s.touching);
    const double kx = 1 / (ar * ar) + 1.5 / (4 * ar * ar), kz = 1.0 + 1 / 1.5;
    EXPECT_NEAR(s.geometry.radius, 1 / std::sqrt(kx * kz), 1e-12 * s.geometry.radius);
  }
}

TEST(EllipsoidContact, HertzRadiusOfPairMatchesTheCurvatureTensors) {
  // The one-division form of R* against the determinant of the summed 2x2
  // curvature tensors, over random triaxial pairs (aspect ratios up to 1000),
  // orientations and normals. Both carry rounding errors that grow with the
  // aspect ratio (against a __float128 evaluation: ~1e-15 up to 3, ~1e-13 up
  // to 30, ~1e-10 up to 1000, for either form).
  Rng rng(29);
  for (double ar : {1.0, 3.0, 30.0, 1000.0}) {
    double worst = 0;
    for (int k = 0; k < 2000; ++k) {
      SymMat3 q[2];
      for (auto& qk : q) {
        const Vector3d a(1.0, rng.uniform(1.0, ar), rng.uniform(1.0, ar));
        qk = quadratic_form(a * rng.uniform(0.1, 10), rng.rotation().toRotationMatrix());
      }
      const Vector3d n = rng.unit_vector();
      Vector3d t1, t2;
      tangent_basis(n, t1, t2);
      const Vector3d qin = form_times(q[0], n), qjn = form_times(q[1], n);
      const double hi2 = n.dot(qin), hj2 = n.dot(qjn), hi = std::sqrt(hi2), hj = std::sqrt(hj2);
      const double expected = hertz_radius(curvature_tensor(q[0], qin, hi2, hi, t1, t2) +
                                           curvature_tensor(q[1], qjn, hj2, hj, t1, t2));
      const double got = hertz_radius_of_pair(q[0], qin, hi2, hi, q[1], qjn, hj2, hj, t1, t2);
      ASSERT_TRUE(std::isfinite(got));
      worst = std::max(worst, std::abs(got - expected) / expected);
    }
    std::printf("aspect ratio <= %g: worst relative difference of R* %.2e\n", ar, worst);
    EXPECT_LT(worst, 1e-14 * ar * ar + 1e-14);
  }
}

TEST(EllipsoidContact, CurvatureTensorMatchesTheSurface) {
  // Independent check of curvature_tensor: sample the surface around the
  // support point and fit the height over the tangent plane,
  // height(xi) = -(1/2) xi^T K xi + O(xi^3).
  Rng rng(23);
  for (int k = 0; k < 50; ++k) {
    const Vector3d a(rng.uniform(0.5, 3), rng.uniform(0.5, 3), rng.uniform(0.5, 3));
    const Mat3 R = rng.rotation().toRotationMatrix();
    const SymMat3 q = quadratic_form(a, R);
    const Vector3d n = rng.unit_vector();
    Vector3d t1, t2;
    tangent_basis(n, t1, t2);
    EXPECT_NEAR(t1.cross(t2).dot(n), 1.0, 1e-15);
    const Eigen::Matrix2d K = curvature_tensor(q, n, t1, t2);
    const Vector3d p = form_times(q, n) / support(q, n);
    // Height of the surface above p along n at tangent offset xi: the
    // ellipsoid point y = p + xi + h n with y^T Q^{-1} y = 1 (solve for h).
    const Mat3 A = to_matrix(q).inverse();
    const double e = 1e-4;
    const double dirs[3][2] = {{1.0, 0.0}, {0.0, 1.0}, {0.6, 0.8}};
    for (const auto& dir : dirs) {
      const double c1 = dir[0], c2 = dir[1];
      const Vector3d xi = e * (c1 * t1 + c2 * t2);
      // quadratic in h: (p+xi+hn)^T A (p+xi+hn) = 1
      const Vector3d b = p + xi;
      const double qa = n.dot(A * n), qb = 2 * n.dot(A * b), qc = b.dot(A * b) - 1;
      const double h = -2 * qc / (qb + std::sqrt(qb * qb - 4 * qa * qc));  // root near 0
      const double expected = -0.5 * e * e * (c1 * c1 * K(0, 0) + 2 * c1 * c2 * K(0, 1) + c2 * c2 * K(1, 1));
      EXPECT_NEAR(h, expected, 1e-3 * std::abs(expected) + 1e-15);
    }
  }
}

}  // namespace
}  // namespace grains::contact
