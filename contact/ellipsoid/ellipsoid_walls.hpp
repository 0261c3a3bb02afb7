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
//
// Finite plane (an annulus of zero thickness, contact/plane.hpp: a disc, or a
// silo floor with its orifice), touched on both faces and on its rims. The
// annulus is not convex, so an ellipsoid can touch it at two places (a long
// grain lying across the orifice rests on both sides of the hole's rim); up to
// two contacts are returned, each with its own history slot:
//  - Face: the plane contact above on the side of the centre. It holds when
//    the foot q0 (on the plane) of the body's deepest point lies on the
//    annulus, as for a sphere whose centre lies over a face.
//  - Rim: a point q of a rim circle inside the body. Along the circle the
//    depth D(theta) = -(signed distance of q from the surface) is maximised:
//    the arcs of the circle inside the body are where the body's quadratic
//    F(q) = (q - c)^T Q^-1 (q - c) (a trigonometric polynomial of degree 2 in
//    theta: at most two arcs) is below 1; on each, the maximum is the root of
//    D' = -n_s . q'(theta), n_s the outward surface normal at the closest
//    point (point_ellipsoid.hpp). overlap = D, normal = -n_s (from the rim
//    into the body, the sphere-annulus normal for a sphere), point = q,
//    R* from the body's curvature there (the edge's own curvature neglected,
//    as for spheres).
//  Without a face contact the maxima on the rim on q0's side count (the
//  hole's if q0 lies in the hole, else the outer one); with one, a rim
//  maximum counts only when the segment from q0 to it crosses the hole (it
//  belongs to another part of the body's section with the sheet; otherwise
//  the face contact already holds that part).
// Slots (a preference; sim/walls/wall_contact_stage.hpp lets a lone contact
// continue the slot that holds history): a face contact 0, a rim contact
// beside it 1; rim contacts by the side of the body's longest axis they lie
// on (0: (point - centre) . v_long >= 0), the second taking the other slot.
#include <Eigen/Core>

#include "contact/contact_geometry.hpp"
#include "contact/ellipsoid/ellipsoid.hpp"
#include "contact/cylinder.hpp"
#include "contact/plane.hpp"

namespace grains::contact {

// Body i = ellipsoid, body j = wall; the normal points from the wall into the
// ellipsoid. `touching` (optional) is set to overlap > 0 (and, for the
// cylinder, the contact point within the wall's extent).
ContactGeometry ellipsoid_plane_contact(const Ellipsoid& body, const Plane& wall,
                                        bool* touching = nullptr);
// The same with the body's form Q already at hand (a DEM scene keeps it per
// particle): R* in closed form, a0 a1 a2 / h^2 with h = sqrt(m^T Q m).
ContactGeometry ellipsoid_plane_contact(const Eigen::Vector3d& centre, const SymMat3& form,
                                        const Eigen::Vector3d& semi_axes, const Plane& wall,
                                        bool* touching = nullptr);
ContactGeometry ellipsoid_cylinder_contact(const Ellipsoid& body, const CylinderSurface& wall,
                                           bool* touching = nullptr);

struct AnnulusContacts {
  int count = 0;            // touching contacts, 0..2
  ContactGeometry g[2];     // g[k] for k < count
  int slot[2] = {0, 1};     // history slot of g[k]: 0 or 1, distinct
  bool face[2] = {false, false};  // g[k] is the face contact (else a rim)
};
AnnulusContacts ellipsoid_annulus_contacts(const Ellipsoid& body, const Annulus& wall);

}  // namespace grains::contact
