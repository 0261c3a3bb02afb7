#pragma once
// Closest point on an ellipsoid surface to a point, and the sphere-ellipsoid
// contact built on it.
//
// In the body frame (semi-axes e_i along the axes, point y) the closest
// surface point is x_i = e_i^2 y_i / (t + e_i^2) where the Lagrange multiplier
// t >= -min e_i^2 solves sum_i (e_i y_i / (t + e_i^2))^2 = 1 (Eberly,
// "Distance from a point to an ellipse, an ellipsoid, or a hyperellipsoid",
// Geometric Tools, 2013). With s = t + e_min^2 this is secular_equation.hpp,
// solved by a monotone Newton iteration; the hard case of a point on a
// symmetry plane inside the body is completed in closed form. Exact (to
// rounding, one step) for spheres, valid inside and outside, no polynomial.
#include <Eigen/Core>

#include "contact/contact_geometry.hpp"
#include "contact/ellipsoid/ellipsoid.hpp"

namespace grains::contact {

struct ClosestPoint {
  Eigen::Vector3d point{0, 0, 0};   // closest point on the surface
  Eigen::Vector3d normal{0, 0, 1};  // outward unit surface normal there
  double signed_distance = 0.0;     // |p - point|, negative when p is inside
  int iterations = 0;               // Newton steps on the secular equation
};

// Body frame: ellipsoid centred at 0 with semi-axes `e` along x, y, z.
ClosestPoint closest_point_on_ellipsoid_body(const Eigen::Vector3d& y, const Eigen::Vector3d& e);

// World frame.
ClosestPoint closest_point_on_ellipsoid(const Eigen::Vector3d& p, const Ellipsoid& body);

// Sphere i (centre, radius) against ellipsoid j. The normal points from the
// ellipsoid towards the sphere (the outward ellipsoid normal at the closest
// point); overlap = radius - signed distance of the sphere centre; point is
// midway between the ellipsoid's closest point and the sphere's deepest
// point; radius = 1/sqrt(det(K_ellipsoid + I/R)) (surface_curvature.hpp).
// `touching` (optional) is set to overlap > 0.
ContactGeometry sphere_ellipsoid_contact(const Eigen::Vector3d& sphere_centre, double sphere_radius,
                                         const Ellipsoid& body, bool* touching = nullptr);

}  // namespace grains::contact
