#pragma once
// Sphere-cylinder wall contact geometry: the lateral surface of a finite
// circular cylinder (end caps are separate planes if a case wants them).
// An "inside" cylinder holds particles within it (a silo); an "outside" one
// keeps them out (a post).
#include <cmath>

#include "contact/contact_geometry.hpp"

namespace grains::contact {

struct CylinderSurface {
  Vec3 base{0, 0, 0};      // a point on the axis
  Vec3 axis{0, 0, 1};      // unit axis direction
  double radius = 1;       // of the surface
  double t_min = -1e300;   // extent along the axis, measured from base
  double t_max = 1e300;
  bool inside = true;      // particles are held inside (a silo) or kept outside (a post)
};

/// Distance of the sphere centre from the surface along its outward (towards
/// the particle) normal; returns false outside the axial extent.
GRAINS_INLINE bool sphere_cylinder(const Vec3& x, double r, const CylinderSurface& c, ContactGeometry& g) {
  const Vec3 rel = x - c.base;
  const double t = rel.dot(c.axis);
  if (t < c.t_min || t > c.t_max) return false;
  const Vec3 radial = rel - c.axis * t;
  const double rho = radial.norm();
  const double overlap = c.inside ? rho + r - c.radius : c.radius + r - rho;
  if (overlap <= 0) return false;
  // On the axis itself the radial direction is undefined: choose a fixed
  // perpendicular so the result stays finite.
  Vec3 e = rho > 0 ? Vec3(radial / rho) : c.axis.unitOrthogonal();
  g.normal = c.inside ? Vec3(-e) : e;
  g.overlap = overlap;
  g.point = c.base + c.axis * t + e * c.radius;
  g.radius = r;  // the wall's own curvature is neglected (documented in docs/physics.md)
  return true;
}

}  // namespace grains::contact
