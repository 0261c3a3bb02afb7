#pragma once
// Ellipsoid against a triangle-mesh surface (contact/mesh/mesh_surface.hpp),
// one contact per physical contact.
//
// Per triangle (plane normal m turned towards the centre; one-sided: the
// front normal), as for the finite planes of ellipsoid_walls.hpp:
//  - none when the body does not cross the triangle's plane
//    (h = sqrt(m^T Q m) <= (c - a).m);
//  - Face: the plane contact of ellipsoid_walls.hpp (overlap h - (c - a).m,
//    normal m, R* = a0 a1 a2 / h^2) when the foot on the plane of the body's
//    deepest point lies on the triangle, or when the depth of the triangle's
//    points inside the body is largest inside it (below);
//  - else Edge or Vertex: the point q of the triangle's boundary deepest
//    inside the body. Along an edge A + t (B - A) the depth
//    D(t) = -(signed distance of q(t) from the surface, point_ellipsoid.hpp)
//    is concave (the distance to the boundary of a convex body), so its
//    maximum on the part of the segment inside the body (where the quadratic
//    (q - c)^T Q^-1 (q - c) < 1: a quadratic in t) is the root of
//    D'(t) = -n_s . (B - A), found by the Illinois method, or an end of the
//    segment (a vertex). overlap = D, normal = -n_s (from the edge into the
//    body), point q, R* from the body's curvature there (the edge's
//    neglected, as for a sphere). The line-to-quadric distance of the
//    seed's course notes, solved as the maximum of a concave function.
// Resolution, as for spheres (mesh_surface.hpp) but with the depth's
// gradient -n_s for the local-maximum test: faces all count, those in the
// same plane (a flat patch) once; an edge counts once, when no triangle
// sharing it is in face contact and the depth does not grow into any of them
// (n_s . t_g >= 0, t_g the direction into triangle g normal to the edge); a
// vertex counts once, when no triangle sharing it is in face contact, no
// edge through it counts and the depth does not grow along any edge from it.
// On a flat patch the result is the plane contact; across a convex ridge the
// overlap passes from the plane measure to the point depth, as at the rims of
// a finite plane.
#include <cstdint>
#include <span>

#include "contact/ellipsoid/ellipsoid.hpp"
#include "contact/mesh/mesh_surface.hpp"

namespace grains::contact {

/// The contacts of ellipsoid `body` (in the mesh's frame) with the triangles
/// `tris` (items of MeshSurface::near(), marked or not: ascending; a superset
/// of those it touches), deepest first; at most
/// `max` written; returns how many there are.
int ellipsoid_mesh_contacts(const MeshSurface& mesh, const Ellipsoid& body, std::span<const std::uint32_t> tris,
                            MeshContact* out, int max);

}  // namespace grains::contact
