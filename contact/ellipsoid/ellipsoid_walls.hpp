#pragma once
// Ellipsoid against the walls of a container: an infinite plane (closed form
// from the support function) and the inside of a finite circular cylinder
// (seed 003's line-to-quadric problem, reduced to the farthest point of the
// ellipsoid's shadow ellipse from the axis).
//
// Plane {x : (x - p0).m = 0}, m the unit normal pointing to the side where the
// ellipsoid lives. With h = sqrt(m^T Q m) the ellipsoid's support radius along
// m, its deepest point is c - Q m / h and
//     overlap = h - (c - p0).m,   normal = m,   R* = 1/sqrt(det K) there.
//
// Cylinder of radius R_c around the axis a + z d (|d| = 1), z in [z_min, z_max]:
// the ellipsoid's projection on the plane normal to d is the ellipse with
// centre c' and form Q' = T^T Q T (T an orthonormal basis of that plane; the
// projection of an ellipsoid in the seed's Q convention is the restriction of
// Q). Its farthest point x* from the axis solves the secular equation
// (secular_equation.hpp) in the ellipse's principal frame; u = x*/|x*| is the
// outward radial direction, the ellipsoid's contact point is its support point
// along u, overlap = |x*| - R_c, normal = -u (from the wall into the
// container), and the wall's curvature -1/R_c around the circumference enters
// R*. Contacts whose point lies outside [z_min, z_max] along the axis are
// reported as not touching (the end caps are planes).
//
// Outside of the cylinder (a post, inside = false): a cylinder is a disc in
// the plane normal to its axis, so the contact is the sphere-ellipsoid one of
// that plane — the point x* of the shadow ellipse closest to the axis (the
// same secular equation, closest instead of farthest point, inside or
// outside the ellipse), n = the ellipse's outward normal there (lifted to 3D,
// pointing towards the axis), the contact point on the body its support point
// along n, overlap = R_c - (signed distance from the axis to the ellipse:
// negative when the axis pierces the body, so the overlap grows continuously
// and the push stays along -n), normal = -n (from the post into the body),
// and the wall's curvature +1/R_c around the circumference enters R*.
#include <Eigen/Core>

#include "contact/contact_geometry.hpp"
#include "contact/ellipsoid/ellipsoid.hpp"

namespace grains::contact {

struct PlaneWall {
  Eigen::Vector3d point{0, 0, 0};
  Eigen::Vector3d normal{0, 0, 1};  // unit, pointing to the particles' side
};

struct CylinderWall {
  Eigen::Vector3d axis_point{0, 0, 0};
  Eigen::Vector3d axis{0, 0, 1};  // unit
  double radius = 1.0;
  double z_min = -1e300, z_max = 1e300;  // extent along the axis from axis_point
  bool inside = true;  // particles held inside (a silo) or kept outside (a post)
};

// Body i = ellipsoid, body j = wall; the normal points from the wall into the
// ellipsoid. `touching` (optional) is set to overlap > 0 (and, for the
// cylinder, the contact point within the wall's extent).
ContactGeometry ellipsoid_plane_contact(const Ellipsoid& body, const PlaneWall& wall,
                                        bool* touching = nullptr);
ContactGeometry ellipsoid_cylinder_contact(const Ellipsoid& body, const CylinderWall& wall,
                                           bool* touching = nullptr);

}  // namespace grains::contact
