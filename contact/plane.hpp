#pragma once
// Sphere-plane contact geometry. A plane is one-sided: particles live on the
// side its unit normal points to.
#include "contact/contact_geometry.hpp"

namespace grains::contact {

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

}  // namespace grains::contact
