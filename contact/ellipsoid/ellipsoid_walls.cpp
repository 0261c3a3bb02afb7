// Ellipsoid-plane and ellipsoid-cylinder contacts: see ellipsoid_walls.hpp.
#include "contact/ellipsoid/ellipsoid_walls.hpp"

#include <cmath>

#include "contact/ellipsoid/secular_equation.hpp"
#include "contact/ellipsoid/surface_curvature.hpp"

namespace grains::contact {

using Eigen::Vector2d;
using Eigen::Vector3d;

ContactGeometry ellipsoid_plane_contact(const Ellipsoid& body, const PlaneWall& wall, bool* touching) {
  const SymMat3 q = body.form();
  const Vector3d& m = wall.normal;
  const Vector3d qm = form_times(q, m);
  const double h = std::sqrt(m.dot(qm));
  ContactGeometry g;
  g.normal = m;
  g.overlap = h - (body.centre - wall.point).dot(m);
  const Vector3d deepest = body.centre - qm / h;
  g.point = deepest + 0.5 * g.overlap * m;
  Vector3d t1, t2;
  tangent_basis(m, t1, t2);
  g.radius = hertz_radius(curvature_tensor(q, m, t1, t2));
  if (touching) *touching = g.overlap > 0.0;
  return g;
}

namespace {

// The post: closest point of the shadow ellipse (principal frame v0, v1,
// semi-axes b0 >= b1, centre cp relative to the axis) to the axis.
ContactGeometry outside_cylinder(const Ellipsoid& body, const CylinderWall& wall, const SymMat3& q,
                                 const Vector3d& t1, const Vector3d& t2, const Vector2d& v0, const Vector2d& v1,
                                 const double (&cp)[2], const double (&b)[2], double b0sq_minus_b1sq,
                                 bool* touching) {
  // The axis seen from the ellipse centre, y = -cp; work with lengths of
  // order one (the answer is homogeneous of degree one).
  const double scale = b[0];
  const double e[2] = {1.0, b[1] / scale};
  const double y[2] = {-cp[0] / scale, -cp[1] / scale};
  // Multiplier referred to the smaller axis (secular_equation.hpp):
  // x_i = e_i^2 y_i / (s + d_i), d_i = e_i^2 - e_1^2.
  const double d[2] = {b0sq_minus_b1sq / (scale * scale), 0.0};
  const double alpha[2] = {e[0] * std::abs(y[0]), e[1] * std::abs(y[1])};
  const double s = secular_root(alpha, d);
  double x[2];
  if (s > 0.0) {
    x[0] = e[0] * e[0] * y[0] / (s + d[0]);
    x[1] = e[1] * e[1] * y[1] / s;
  } else {
    // Axis inside the ellipse on its major axis line: the closest boundary
    // points are symmetric about it; take the +v1 one.
    x[0] = d[0] > 0.0 ? e[0] * e[0] * y[0] / d[0] : 0.0;
    x[1] = e[1] * std::sqrt(std::max(0.0, 1.0 - x[0] * x[0]));
  }
  const double inside_ellipse = (y[0] / e[0]) * (y[0] / e[0]) + (y[1] / e[1]) * (y[1] / e[1]);
  const double dist = std::hypot(y[0] - x[0], y[1] - x[1]) * scale;
  const double signed_distance = inside_ellipse < 1.0 ? -dist : dist;
  // Outward normal of the ellipse at x (principal frame), lifted to 3D.
  Vector2d n2(x[0] / (e[0] * e[0]), x[1] / (e[1] * e[1]));
  n2 = (n2[0] * v0 + n2[1] * v1).normalized();
  const Vector3d n = n2[0] * t1 + n2[1] * t2;  // body's outward normal, towards the axis
  const Vector3d qn = form_times(q, n);
  const double h = std::sqrt(n.dot(qn));
  const Vector3d contact_on_body = body.centre + qn / h;
  ContactGeometry g;
  g.normal = -n;
  g.overlap = wall.radius - signed_distance;
  g.point = contact_on_body - 0.5 * g.overlap * n;
  const Vector3d& dax = wall.axis;
  const Vector3d circ = dax.cross(n);
  const Eigen::Matrix2d k_body = curvature_tensor(q, n, dax, circ);
  Eigen::Matrix2d k = k_body;
  k(1, 1) += 1.0 / wall.radius;  // convex post
  g.radius = hertz_radius(k);
  if (touching) {
    const double zc = (contact_on_body - wall.axis_point).dot(dax);
    *touching = g.overlap > 0.0 && zc >= wall.z_min && zc <= wall.z_max;
  }
  return g;
}

}  // namespace

ContactGeometry ellipsoid_cylinder_contact(const Ellipsoid& body, const CylinderWall& wall,
                                           bool* touching) {
  const SymMat3 q = body.form();
  const Vector3d& d = wall.axis;
  Vector3d t1, t2;
  tangent_basis(d, t1, t2);
  // Shadow ellipse in the plane normal to the axis.
  const Vector3d rel = body.centre - wall.axis_point;
  const Vector2d c(rel.dot(t1), rel.dot(t2));
  const double a00 = t1.dot(form_times(q, t1)), a01 = t1.dot(form_times(q, t2)), a11 = t2.dot(form_times(q, t2));
  // Principal frame: b0^2 >= b1^2, eigenvector v0 at angle theta.
  const double mean = 0.5 * (a00 + a11);
  const double rad = std::hypot(0.5 * (a00 - a11), a01);
  const double b0sq = mean + rad;
  const double b1sq = (a00 * a11 - a01 * a01) / b0sq;
  const double theta = 0.5 * std::atan2(2.0 * a01, a00 - a11);
  const Vector2d v0(std::cos(theta), std::sin(theta)), v1(-v0[1], v0[0]);
  const double cp[2] = {c.dot(v0), c.dot(v1)};
  const double b[2] = {std::sqrt(b0sq), std::sqrt(b1sq)};
  if (!wall.inside) return outside_cylinder(body, wall, q, t1, t2, v0, v1, cp, b, 2.0 * rad, touching);
  // Farthest point c + z: z_i = b_i^2 cp_i / (s + d_i), d_i = b0^2 - b_i^2.
  const double dd[2] = {0.0, 2.0 * rad};
  const double alpha[2] = {b[0] * std::abs(cp[0]), b[1] * std::abs(cp[1])};
  const double s = secular_root(alpha, dd);
  double z[2];
  if (s > 0.0) {
    z[0] = b0sq * cp[0] / s;
    z[1] = b1sq * cp[1] / (s + dd[1]);
  } else {
    // Centre on the ellipse's minor axis line through the cylinder axis: the
    // farthest points are symmetric; take the one on the +v0 side.
    z[1] = dd[1] > 0.0 ? b1sq * cp[1] / dd[1] : 0.0;
    z[0] = b[0] * std::sqrt(std::max(0.0, 1.0 - (z[1] / b[1]) * (z[1] / b[1])));
  }
  const Vector2d x = c + z[0] * v0 + z[1] * v1;
  const double rho = x.norm();
  const Vector2d u2 = rho > 0.0 ? Vector2d(x / rho) : Vector2d(v0);
  const Vector3d u = u2[0] * t1 + u2[1] * t2;  // outward radial direction
  const Vector3d qu = form_times(q, u);
  const double h = std::sqrt(u.dot(qu));
  const Vector3d contact_on_body = body.centre + qu / h;
  ContactGeometry g;
  g.normal = -u;
  g.overlap = rho - wall.radius;
  g.point = contact_on_body - 0.5 * g.overlap * u;
  // Curvatures in the tangent plane at the contact: the axis d and the
  // circumferential direction e = d x u (both orthogonal to u).
  const Vector3d e = d.cross(u);
  const Eigen::Matrix2d k_body = curvature_tensor(q, u, d, e);
  Eigen::Matrix2d k = k_body;
  k(1, 1) -= 1.0 / wall.radius;  // concave wall
  // A body as curved as the wall (conforming contact) would give R* = inf;
  // floor the relative curvature at 1e-3 of the body's own.
  g.radius = hertz_radius(k, 1e-3 * std::min(k_body(0, 0), k_body(1, 1)));
  if (touching) {
    const double zc = (contact_on_body - wall.axis_point).dot(d);
    *touching = g.overlap > 0.0 && zc >= wall.z_min && zc <= wall.z_max;
  }
  return g;
}

}  // namespace grains::contact
