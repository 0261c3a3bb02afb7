// Ellipsoid against a plane, inside a cylinder and outside one (a post), and
// against a finite plane (an annulus: a disc or a floor with an orifice):
// closed forms for spheres and aligned spheroids, the sphere-annulus contact
// for round bodies, and brute-force sampling for general poses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "contact/ellipsoid/ellipsoid_walls.hpp"
#include "contact/ellipsoid/point_ellipsoid.hpp"
#include "contact/ellipsoid/surface_curvature.hpp"
#include "contact/plane.hpp"
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
  ContactGeometry g = ellipsoid_plane_contact(ball, Plane{}, &touching);
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
  g = ellipsoid_plane_contact(s, Plane{}, &touching);
  EXPECT_TRUE(touching);
  EXPECT_NEAR(g.overlap, 0.1, 1e-14);
  EXPECT_NEAR(g.radius, 1.0 / 3.0, 1e-14);
  // Lying on its flank: radii b and a^2/b, R* = sqrt(b * a^2/b) = a.
  s.orientation = Quat::Identity();
  s.centre = Vector3d(0, 0, 1.05);
  g = ellipsoid_plane_contact(s, Plane{}, &touching);
  EXPECT_FALSE(touching);
  EXPECT_NEAR(g.overlap, -0.05, 1e-15);
  EXPECT_NEAR(g.radius, 3.0, 1e-14);
}

TEST(EllipsoidPlane, ClosedFormHertzRadiusMatchesTheCurvatureTensor) {
  // R* = a0 a1 a2 / h^2 against 1/sqrt(det K) of the 2x2 curvature tensor at
  // the deepest point, over random poses and aspect ratios up to 1000; the
  // overload that takes the form gives the same contact bit for bit.
  Rng rng(41);
  for (double ar : {1.0, 3.0, 30.0, 1000.0}) {
    double worst = 0;
    for (int k = 0; k < 2000; ++k) {
      Ellipsoid b;
      b.semi_axes = Vector3d(1.0, rng.uniform(1.0, ar), rng.uniform(1.0, ar)) * rng.uniform(0.1, 10);
      b.orientation = rng.rotation();
      b.centre = rng.unit_vector() * rng.uniform(0, 2);
      const Plane wall{Vector3d(0.1, -0.2, 0.3), rng.unit_vector()};
      bool touching = false, touching_form = false;
      const ContactGeometry g = ellipsoid_plane_contact(b, wall, &touching);
      const ContactGeometry f = ellipsoid_plane_contact(b.centre, b.form(), b.semi_axes, wall, &touching_form);
      ASSERT_EQ(touching, touching_form);
      ASSERT_EQ(g.overlap, f.overlap);
      ASSERT_EQ(g.radius, f.radius);
      ASSERT_EQ(g.point, f.point);
      Vector3d t1, t2;
      tangent_basis(wall.normal, t1, t2);
      const double expected = hertz_radius(curvature_tensor(b.form(), wall.normal, t1, t2));
      worst = std::max(worst, std::abs(g.radius - expected) / expected);
    }
    std::printf("aspect ratio <= %g: worst relative difference of R* %.2e\n", ar, worst);
    EXPECT_LT(worst, 1e-14 * ar * ar + 1e-14);
  }
}

TEST(EllipsoidPlane, DeepestPointAgainstSampling) {
  Rng rng(40);
  for (int k = 0; k < 50; ++k) {
    Ellipsoid b;
    b.semi_axes = Vector3d(rng.uniform(0.2, 3), rng.uniform(0.2, 3), rng.uniform(0.2, 3));
    b.orientation = rng.rotation();
    b.centre = rng.unit_vector() * 2;
    Plane w;
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
  CylinderSurface w;
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
  w.t_min = 1.0;
  ellipsoid_cylinder_contact(ball, w, &touching);
  EXPECT_FALSE(touching);
}

TEST(EllipsoidCylinder, FarthestPointAgainstSampling) {
  Rng rng(41);
  for (int k = 0; k < 60; ++k) {
    CylinderSurface w;
    w.axis = rng.unit_vector();
    w.base = Vector3d(rng.normal(), rng.normal(), rng.normal());
    w.radius = 6;
    Ellipsoid b;
    b.semi_axes = Vector3d(rng.uniform(0.2, 3), rng.uniform(0.2, 3), rng.uniform(0.2, 3));
    b.orientation = rng.rotation();
    Vector3d off = rng.unit_vector();
    off -= off.dot(w.axis) * w.axis;
    // Half the cases with the centre exactly on the axis (the hard case).
    b.centre = w.base + (k % 2 ? rng.uniform(0, 3) : 0.0) * off + rng.normal() * w.axis;
    const ContactGeometry g = ellipsoid_cylinder_contact(b, w);
    double far = 0;
    for_surface_samples(b, 150, [&](const Vector3d& x) {
      const Vector3d rel = x - w.base;
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
  CylinderSurface w;
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
  CylinderSurface w;
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
  CylinderSurface w;
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
    CylinderSurface w;
    w.axis = rng.unit_vector();
    w.base = Vector3d(rng.normal(), rng.normal(), rng.normal());
    w.radius = rng.uniform(0.1, 2);
    w.inside = false;
    Ellipsoid b;
    b.semi_axes = Vector3d(rng.uniform(0.2, 3), rng.uniform(0.2, 3), rng.uniform(0.2, 3));
    b.orientation = rng.rotation();
    Vector3d off = rng.unit_vector();
    off -= off.dot(w.axis) * w.axis;
    off.normalize();
    b.centre = w.base + (k % 8 == 0 ? 0.0 : rng.uniform(0, 5)) * off + rng.normal() * w.axis;
    const ContactGeometry g = ellipsoid_cylinder_contact(b, w);
    ASSERT_TRUE(std::isfinite(g.overlap) && std::isfinite(g.radius) && g.normal.allFinite());
    EXPECT_NEAR(g.normal.dot(w.axis), 0.0, 1e-13);
    EXPECT_NEAR(g.normal.norm(), 1.0, 1e-14);
    EXPECT_GT(g.radius, 0.0);
    double near = INFINITY;
    for_surface_samples(b, 150, [&](const Vector3d& x) {
      const Vector3d rel = x - w.base;
      near = std::min(near, (rel - rel.dot(w.axis) * w.axis).norm());
    });
    // Is the axis through the body? (Its closest approach to the centre, in
    // the body frame, inside the unit ball.)
    const Mat3 R = b.orientation.toRotationMatrix();
    const Vector3d rel = b.centre - w.base;
    const Vector3d foot = w.base + rel.dot(w.axis) * w.axis;
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

// ---- Finite planes (annuli) ------------------------------------------------

Annulus random_annulus(Rng& rng) {
  Annulus a;
  a.normal = rng.unit_vector();
  a.centre = Vector3d(rng.normal(), rng.normal(), rng.normal());
  const int kind = static_cast<int>(rng.uniform() * 3);  // hole only, disc, ring
  if (kind != 1) a.r_in = rng.uniform(0.5, 3);
  if (kind != 0) a.r_out = a.r_in + rng.uniform(1, 4);
  return a;
}

TEST(EllipsoidAnnulus, RoundBodyIsTheSphereAnnulusContact) {
  // A round ellipsoid in any orientation touches an annulus exactly where a
  // sphere does: same overlap and normal; the rim point is the same point,
  // the face point lies half the overlap behind the sphere's foot point.
  Rng rng(71);
  int faces = 0, rims = 0;
  for (int k = 0; k < 4000; ++k) {
    const Annulus a = random_annulus(rng);
    Ellipsoid b;
    const double r = rng.uniform(0.2, 2);
    b.semi_axes = Vector3d::Constant(r);
    b.orientation = rng.rotation();
    // Centres near the sheet, over the faces, the hole and the rims.
    Vector3d e1, e2;
    tangent_basis(a.normal, e1, e2);
    const double phi = rng.uniform(0, 2 * std::numbers::pi);
    const double rho_max = std::isfinite(a.r_out) ? a.r_out + r : a.r_in + 3;
    const double rho = rng.uniform(0, rho_max);
    b.centre = a.centre + rho * (std::cos(phi) * e1 + std::sin(phi) * e2) + rng.uniform(-1.2, 1.2) * r * a.normal;
    ContactGeometry gs;
    const bool sphere = sphere_annulus(b.centre, r, a, gs);
    const AnnulusContacts c = ellipsoid_annulus_contacts(b, a);
    ASSERT_EQ(c.count, sphere ? 1 : 0) << "pose " << k << " r " << r << " centre " << b.centre.transpose() << " annulus "
                                        << a.centre.transpose() << " n " << a.normal.transpose() << " " << a.r_in << " "
                                        << a.r_out << " ov " << c.g[0].overlap << " " << c.g[1].overlap << " face "
                                        << c.face[0] << c.face[1] << " pts " << c.g[0].point.transpose() << " / "
                                        << c.g[1].point.transpose();
    if (!sphere) continue;
    const ContactGeometry& g = c.g[0];
    EXPECT_NEAR(g.overlap, gs.overlap, 1e-12 * r) << "pose " << k;
    EXPECT_LT((g.normal - gs.normal).norm(), 1e-9) << "pose " << k;
    EXPECT_NEAR(g.radius, r, 1e-12 * r);
    const Vector3d p = c.face[0] ? Vector3d(g.point + 0.5 * g.overlap * g.normal) : g.point;
    EXPECT_LT((p - gs.point).norm(), 1e-9 * r) << "pose " << k;
    (c.face[0] ? faces : rims)++;
  }
  EXPECT_GT(faces, 200);
  EXPECT_GT(rims, 200);
}

TEST(EllipsoidAnnulus, OverAFaceItIsThePlaneContactOnEitherSide) {
  Annulus a;
  a.r_in = 1;
  a.r_out = 20;
  Ellipsoid b;
  b.semi_axes = Vector3d(2, 0.5, 0.3);
  b.orientation = Quat(Eigen::AngleAxisd(0.3, Vector3d(1, 1, 0).normalized()));
  for (const double side : {1.0, -1.0}) {
    b.centre = Vector3d(8, 3, side * 0.4);
    const AnnulusContacts c = ellipsoid_annulus_contacts(b, a);
    ASSERT_EQ(c.count, 1);
    EXPECT_TRUE(c.face[0]);
    EXPECT_EQ(c.slot[0], 0);
    bool touching = false;
    const ContactGeometry p = ellipsoid_plane_contact(b, Plane{a.centre, side * a.normal}, &touching);
    ASSERT_TRUE(touching);
    EXPECT_EQ(c.g[0].overlap, p.overlap);
    EXPECT_EQ(c.g[0].normal, p.normal);
    EXPECT_EQ(c.g[0].point, p.point);
    EXPECT_EQ(c.g[0].radius, p.radius);
  }
  // Far from the sheet: nothing.
  b.centre = Vector3d(8, 3, 2.5);
  EXPECT_EQ(ellipsoid_annulus_contacts(b, a).count, 0);
}

TEST(EllipsoidAnnulus, NeedleAcrossTheOrificeRestsOnBothSidesOfTheRim) {
  // A prolate spheroid (3, 0.3, 0.3) lying across a hole of radius 1, 0.03
  // below the sheet: the rim cuts it around (+-1, 0, 0), two
  // contacts, mirror images, in distinct slots, pushing up and inwards.
  Annulus a;
  a.r_in = 1;
  Ellipsoid b;
  b.semi_axes = Vector3d(3, 0.3, 0.3);
  b.centre = Vector3d(0, 0, 0.27);
  const AnnulusContacts c = ellipsoid_annulus_contacts(b, a);
  ASSERT_EQ(c.count, 2);
  EXPECT_FALSE(c.face[0]);
  EXPECT_FALSE(c.face[1]);
  EXPECT_NE(c.slot[0], c.slot[1]);
  EXPECT_NEAR(c.g[0].overlap, c.g[1].overlap, 1e-13);
  EXPECT_NEAR(c.g[0].point.x(), -c.g[1].point.x(), 1e-12);
  EXPECT_NEAR(std::abs(c.g[0].point.x()), 1.0, 1e-12);
  EXPECT_NEAR(c.g[0].point.y(), 0.0, 1e-12);
  EXPECT_LT((c.g[0].normal + c.g[1].normal - Vector3d(0, 0, 2 * c.g[0].normal.z())).norm(), 1e-12);
  EXPECT_GT(c.g[0].normal.z(), 0.99);
  // The depth at the rim: the point (1, 0, 0) inside the body, to rounding.
  const ClosestPoint cp = closest_point_on_ellipsoid(Vector3d(1, 0, 0), b);
  EXPECT_NEAR(c.g[0].overlap, -cp.signed_distance, 1e-14);
  // The slot follows the side of the long axis the contact lies on.
  const int right = c.g[0].point.x() > 0 ? 0 : 1;
  EXPECT_EQ(c.slot[right], 0);
  // Turned to stand upright in the hole, the same needle falls through it.
  b.orientation = Quat(Eigen::AngleAxisd(std::numbers::pi / 2, Vector3d(0, 1, 0)));
  b.centre = Vector3d(0.2, 0.1, 0);
  EXPECT_EQ(ellipsoid_annulus_contacts(b, a).count, 0);
}

// Depth of point q inside the body (negative outside).
double depth(const Vector3d& q, const Ellipsoid& b) { return -closest_point_on_ellipsoid(q, b).signed_distance; }

TEST(EllipsoidAnnulus, RimDepthAgainstSampling) {
  // Bodies straddling a hole's rim with no face contact: the deepest contact
  // is the deepest of 20,000 points sampled along the rim (to their spacing),
  // and every contact is a local maximum of the depth along it.
  Rng rng(72);
  int tested = 0, pairs = 0;
  for (int k = 0; k < 400; ++k) {
    Annulus a;
    a.normal = rng.unit_vector();
    a.centre = Vector3d(rng.normal(), rng.normal(), rng.normal());
    a.r_in = rng.uniform(0.5, 3);
    Ellipsoid b;
    b.semi_axes = Vector3d(rng.log_uniform(0.05, 3), rng.log_uniform(0.05, 3), rng.log_uniform(0.05, 3));
    b.orientation = rng.rotation();
    Vector3d e1, e2;
    tangent_basis(a.normal, e1, e2);
    const double phi = rng.uniform(0, 2 * std::numbers::pi);
    b.centre = a.centre + rng.uniform(0, a.r_in + 0.3) * (std::cos(phi) * e1 + std::sin(phi) * e2) +
               rng.uniform(-0.5, 0.5) * b.semi_axes.minCoeff() * a.normal;
    const AnnulusContacts c = ellipsoid_annulus_contacts(b, a);
    if (c.count == 0 || c.face[0]) continue;
    ++tested;
    pairs += c.count == 2;
    double best = -INFINITY;
    constexpr int S = 20000;
    for (int j = 0; j < S; ++j) {
      const double t = 2 * std::numbers::pi * j / S;
      best = std::max(best, depth(a.centre + a.r_in * (std::cos(t) * e1 + std::sin(t) * e2), b));
    }
    const double scale = b.semi_axes.maxCoeff();
    EXPECT_GE(c.g[0].overlap, best - 1e-12 * scale) << "pose " << k;
    // Sampling resolution: a deep maximum can sit on the body's medial ridge,
    // where the depth falls off linearly (slope <= 1) on both sides.
    EXPECT_LE(c.g[0].overlap, best + 2 * std::numbers::pi * a.r_in / S) << "pose " << k;
    for (int m = 0; m < c.count; ++m) {
      const ContactGeometry& g = c.g[m];
      ASSERT_TRUE(g.normal.allFinite() && std::isfinite(g.overlap) && std::isfinite(g.radius));
      EXPECT_NEAR((g.point - a.centre).norm(), a.r_in, 1e-12 * a.r_in);
      EXPECT_NEAR(g.overlap, depth(g.point, b), 1e-13 * scale);
      // A local maximum: nearby rim points are no deeper.
      const Vector3d rel = g.point - a.centre;
      const Vector3d tan = a.normal.cross(rel).normalized();
      for (const double dt : {1e-4, -1e-4}) {
        const double ang = dt;
        const Vector3d q = a.centre + std::cos(ang) * rel + std::sin(ang) * a.r_in * tan;
        EXPECT_LE(depth(q, b), g.overlap + 1e-12 * scale) << "pose " << k;
      }
    }
  }
  EXPECT_GT(tested, 100);
  EXPECT_GT(pairs, 3);
}

TEST(EllipsoidAnnulus, OverlapIsContinuousAcrossTheRim) {
  // A tilted spheroid slid over the orifice's rim, from the floor to the
  // hole: the deepest overlap changes in proportion to the step when the
  // contact passes from the face to the rim and when it leaves the rim (no
  // jump).
  Annulus a;
  a.r_in = 1;
  Ellipsoid b;
  b.semi_axes = Vector3d(0.6, 0.25, 0.2);
  b.orientation = Quat(Eigen::AngleAxisd(0.4, Vector3d(0, 1, 0)) * Eigen::AngleAxisd(0.7, Vector3d(0, 0, 1)));
  const double h = 0.5 * 1e-4;
  double last = NAN;
  bool was_face = true, switched = false;
  for (double x = 2.0; x > 0.2; x -= h) {
    b.centre = Vector3d(x, 0.05, 0.0);
    // Keep the body 0.01 deep in the floor's plane: its support along z.
    const SymMat3 q = b.form();
    b.centre.z() = std::sqrt(q[5]) - 0.01;
    const AnnulusContacts c = ellipsoid_annulus_contacts(b, a);
    double deepest = 0;  // no contact: the body is over the hole, clear of the rim
    for (int m = 0; m < c.count; ++m) deepest = std::max(deepest, c.g[m].overlap);
    if (!std::isnan(last)) {
      EXPECT_LT(std::abs(deepest - last), 2 * h) << "x = " << x;
    }
    last = deepest;
    if (c.count == 0) break;
    if (was_face && !c.face[0]) switched = true;
    was_face = c.face[0];
  }
  EXPECT_TRUE(switched);
  EXPECT_EQ(last, 0.0) << "never cleared the rim";
}

TEST(EllipsoidAnnulus, HardPosesStayFinite) {
  // Aspect ratios up to 1e3, centres in the sheet, on the hole's axis, bodies
  // engulfing the whole rim: finite results, at most two contacts.
  Rng rng(73);
  for (int k = 0; k < 3000; ++k) {
    Annulus a = random_annulus(rng);
    Ellipsoid b;
    const double big = rng.uniform(0.1, 3);
    b.semi_axes = Vector3d(big, big / rng.log_uniform(1, 1e3), big / rng.log_uniform(1, 1e3));
    b.orientation = rng.rotation();
    const int where = k % 3;
    Vector3d e1, e2;
    tangent_basis(a.normal, e1, e2);
    if (where == 0) b.centre = a.centre;  // on the axis, in the sheet
    else if (where == 1) b.centre = a.centre + a.r_in * e1 + rng.uniform(-1, 1) * big * a.normal;  // on the rim
    else b.centre = a.centre + rng.uniform(0, 4) * e2;  // in the sheet
    const AnnulusContacts c = ellipsoid_annulus_contacts(b, a);
    ASSERT_LE(c.count, 2);
    for (int m = 0; m < c.count; ++m) {
      ASSERT_TRUE(std::isfinite(c.g[m].overlap) && c.g[m].overlap > 0) << "pose " << k;
      ASSERT_TRUE(c.g[m].normal.allFinite() && std::abs(c.g[m].normal.norm() - 1) < 1e-12) << "pose " << k;
      ASSERT_TRUE(c.g[m].point.allFinite() && std::isfinite(c.g[m].radius) && c.g[m].radius > 0) << "pose " << k;
    }
    if (c.count == 2) {
      EXPECT_NE(c.slot[0], c.slot[1]);
    }
  }
  // A round body larger than the hole, centred on it: one contact, the whole
  // rim inside it.
  Annulus hole;
  hole.r_in = 0.5;
  Ellipsoid ball;
  ball.semi_axes = Vector3d::Constant(1);
  ball.centre = Vector3d(0, 0, 0.8);
  const AnnulusContacts c = ellipsoid_annulus_contacts(ball, hole);
  ASSERT_EQ(c.count, 1);
  EXPECT_NEAR(c.g[0].overlap, 1 - std::hypot(0.5, 0.8), 1e-14);
}

}  // namespace
}  // namespace grains::contact
