#pragma once
// Sphere-plane contact geometry. An infinite plane is one-sided: particles
// live on the side its unit normal points to. A finite plane (an annulus: a
// disc of outer radius r_out about a centre, with an optional circular hole
// of radius r_in, e.g. the flat bottom of a silo with its orifice) has zero
// thickness and two faces: a sphere touches the point of the annulus nearest
// its centre, on either face, on the rim of the hole or on the outer rim.
#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_geometry.hpp"

namespace grains::contact {

/// An infinite one-sided plane: particles live on the side `normal` points to.
struct Plane {
  Vec3 point{0, 0, 0};
  Vec3 normal{0, 0, 1};  // unit
};

/// Signed distance of point x from the plane (point p, unit normal n).
GRAINS_INLINE double plane_distance(const Vec3& x, const Vec3& p, const Vec3& n) { return n.dot(x - p); }

/// Fills g (normal = plane normal, from the wall towards the sphere) and returns
/// true when the sphere (x, r) touches the plane. R* is the sphere radius.
GRAINS_INLINE bool sphere_plane(const Vec3& x, double r, const Vec3& p, const Vec3& n, ContactGeometry& g) {
  const double dist = plane_distance(x, p, n);
  if (dist >= r) return false;
  g.normal = n;
  g.overlap = r - dist;
  g.point = x - n * dist;  // foot of the centre on the plane
  g.radius = r;
  return true;
}

/// A flat annulus: the points c + rho e with e a unit vector normal to n and
/// r_in <= rho <= r_out (r_in = 0: a full disc; r_out = infinity: a plane
/// with a hole).
struct Annulus {
  Vec3 centre{0, 0, 0};
  Vec3 normal{0, 0, 1};  // unit
  double r_in = 0;
  double r_out = std::numeric_limits<double>::infinity();
};

/// The point of the annulus nearest to x.
GRAINS_INLINE Vec3 annulus_nearest(const Vec3& x, const Annulus& a) {
  const Vec3 rel = x - a.centre;
  const Vec3 radial = rel - a.normal * a.normal.dot(rel);
  const double rho = radial.norm();
  if (rho >= a.r_in && rho <= a.r_out) return a.centre + radial;  // over a face: the foot of x
  // On the axis of a hole every rim point is as near as another: pick a fixed
  // one so the result stays finite and deterministic.
  const Vec3 e = rho > 0 ? Vec3(radial / rho) : a.normal.unitOrthogonal();
  return a.centre + e * std::clamp(rho, a.r_in, a.r_out);
}

/// Fills g and returns true when the sphere (x, r) touches the annulus. The
/// normal points from the nearest point of the annulus to the centre (the
/// face normal, on the particle's side, over a face; tilted over a rim); R*
/// is the sphere radius (the rim's own curvature is neglected, as for the
/// cylinder wall).
GRAINS_INLINE bool sphere_annulus(const Vec3& x, double r, const Annulus& a, ContactGeometry& g) {
  const Vec3 q = annulus_nearest(x, a);
  const Vec3 d = x - q;
  const double d2 = d.squaredNorm();
  if (d2 >= r * r) return false;
  const double dist = std::sqrt(d2);
  // A centre exactly in the sheet: push it to the front (normal) side.
  g.normal = dist > 0 ? Vec3(d / dist) : a.normal;
  g.overlap = r - dist;
  g.point = q;
  g.radius = r;
  return true;
}

}  // namespace grains::contact
