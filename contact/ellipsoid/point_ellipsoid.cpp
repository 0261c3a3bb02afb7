// Closest point on an ellipsoid: see point_ellipsoid.hpp.
#include "contact/ellipsoid/point_ellipsoid.hpp"

#include <algorithm>
#include <cmath>

#include "contact/ellipsoid/secular_equation.hpp"
#include "contact/ellipsoid/surface_curvature.hpp"

namespace grains::contact {

using Eigen::Vector3d;

ClosestPoint closest_point_on_ellipsoid_body(const Vector3d& y_in, const Vector3d& e_in) {
  // Work with lengths of order one: the answer is homogeneous of degree one.
  const double scale = e_in.maxCoeff();
  const Vector3d e = e_in / scale, y = y_in / scale;
  int k = 0;  // the smallest axis is the reference of the multiplier s
  for (int i = 1; i < 3; ++i)
    if (e[i] < e[k]) k = i;
  double alpha[3], d[3];
  for (int i = 0; i < 3; ++i) {
    alpha[i] = e[i] * std::abs(y[i]);
    d[i] = (e[i] - e[k]) * (e[i] + e[k]);  // e_i^2 - e_k^2 without cancellation
  }
  ClosestPoint cp;
  const double s = secular_root(alpha, d, &cp.iterations);
  Vector3d x;
  if (s > 0.0) {
    for (int i = 0; i < 3; ++i) x[i] = e[i] * e[i] * y[i] / (s + d[i]);
  } else {
    // Hard case: inside, on the symmetry plane(s) through the shortest axes.
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      x[i] = d[i] > 0.0 ? e[i] * e[i] * y[i] / d[i] : 0.0;
      sum += (x[i] / e[i]) * (x[i] / e[i]);
    }
    x[k] = e[k] * std::sqrt(std::max(0.0, 1.0 - sum));
  }
  Vector3d grad(x[0] / (e[0] * e[0]), x[1] / (e[1] * e[1]), x[2] / (e[2] * e[2]));
  cp.normal = grad / grad.norm();
  const double inside = (y[0] / e[0]) * (y[0] / e[0]) + (y[1] / e[1]) * (y[1] / e[1]) +
                        (y[2] / e[2]) * (y[2] / e[2]);
  const double dist = (y - x).norm() * scale;
  cp.signed_distance = inside < 1.0 ? -dist : dist;
  cp.point = x * scale;
  return cp;
}

ClosestPoint closest_point_on_ellipsoid(const Vector3d& p, const Ellipsoid& body) {
  const Mat3 R = body.orientation.toRotationMatrix();
  ClosestPoint cp = closest_point_on_ellipsoid_body(R.transpose() * (p - body.centre), body.semi_axes);
  cp.point = body.centre + R * cp.point;
  cp.normal = R * cp.normal;
  return cp;
}

ContactGeometry sphere_ellipsoid_contact(const Vector3d& centre, double radius, const Ellipsoid& body,
                                         bool* touching) {
  const ClosestPoint cp = closest_point_on_ellipsoid(centre, body);
  ContactGeometry g;
  g.normal = cp.normal;
  g.overlap = radius - cp.signed_distance;
  g.point = 0.5 * (cp.point + centre - radius * cp.normal);
  Vector3d t1, t2;
  tangent_basis(cp.normal, t1, t2);
  Eigen::Matrix2d k = curvature_tensor(body.form(), cp.normal, t1, t2);
  k(0, 0) += 1.0 / radius;
  k(1, 1) += 1.0 / radius;
  g.radius = hertz_radius(k);
  if (touching) *touching = g.overlap > 0.0;
  return g;
}

}  // namespace grains::contact
