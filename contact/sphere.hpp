#pragma once
// Sphere-sphere contact geometry.
#include <cmath>

#include "contact/contact_geometry.hpp"

namespace grains::contact {

/// Fills g and returns true when spheres (xi, ri) and (xj, rj) overlap.
/// The normal points from j to i; the contact point is the middle of the
/// overlap lens along the line of centres; R* = ri rj / (ri + rj).
GRAINS_INLINE bool sphere_sphere(const Vec3& xi, double ri, const Vec3& xj, double rj, ContactGeometry& g) {
  const Vec3 d = xi - xj;
  const double rs = ri + rj;
  const double d2 = d.squaredNorm();
  if (d2 >= rs * rs) return false;
  const double dist = std::sqrt(d2);
  // Coincident centres: any direction is as good as another; pick +z so the
  // result is finite and deterministic.
  g.normal = dist > 0 ? Vec3(d * (1.0 / dist)) : Vec3(0, 0, 1);
  g.overlap = rs - dist;
  g.point = xj + g.normal * (rj - 0.5 * g.overlap);
  g.radius = ri * rj / rs;
  return true;
}

}  // namespace grains::contact
