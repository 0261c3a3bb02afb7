#pragma once
// Curvature of an ellipsoid surface at the point with a given outward normal,
// and the Hertz equivalent radius of two curved surfaces in contact.
//
// For E = { m : (m-c)^T Q^{-1} (m-c) <= 1 } the point with outward unit normal
// n is p = c + Q n / h, h = sqrt(n^T Q n) (the support point). The second
// fundamental form there is II(t, t) = h t^T Q^{-1} t for tangent t. With an
// orthonormal tangent basis T = [t1 t2], the 2x2 curvature tensor is
//     K = h (T^T Q^{-1} T) = h (T^T Q T - v v^T / h^2)^{-1},  v = T^T Q n,
// (block inverse of [T n]^T Q [T n]); no 3x3 inverse is needed. A sphere of
// radius a gives K = I / a.
//
// Hertz: near the contact the gap between two convex surfaces is
// (1/2) xi^T (K1 + K2) xi; the equivalent radius of the Hertz law is
// R* = (R' R'')^{1/2} = 1 / sqrt(det(K1 + K2)) (Johnson, Contact Mechanics,
// 1985, section 4.2; the elliptic-integral correction for non-circular
// contact areas, within a few percent for principal-radius ratios below ~5,
// is neglected). For two spheres this is a1 a2 / (a1 + a2).
#include <Eigen/Core>
#include <array>
#include <cmath>

#include "contact/ellipsoid/ellipsoid.hpp"
#include "contact/ellipsoid/pw85_kernel.hpp"

namespace grains::contact {

// Orthonormal t1, t2 with t1 x t2 = n (n unit).
inline void tangent_basis(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2) {
  pw85_kernel::tangent_basis(n.data(), t1.data(), t2.data());
}

// Curvature tensor of ellipsoid form q at its support point in direction n,
// expressed in the tangent basis (t1, t2) (both orthogonal to n), given
// qn = Q n, h2 = n^T Q n and h = sqrt(h2) (the support point needs them too).
inline Eigen::Matrix2d curvature_tensor(const SymMat3& q, const Eigen::Vector3d& qn, double h2, double h,
                                        const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  const Eigen::Vector3d qt1 = form_times(q, t1), qt2 = form_times(q, t2);
  const double v1 = t1.dot(qn), v2 = t2.dot(qn);
  const double ih2 = 1.0 / h2;
  const double m11 = t1.dot(qt1) - v1 * v1 * ih2;
  const double m12 = t1.dot(qt2) - v1 * v2 * ih2;
  const double m22 = t2.dot(qt2) - v2 * v2 * ih2;
  const double det = m11 * m22 - m12 * m12;
  const double scale = h / det;
  Eigen::Matrix2d k;
  k << m22 * scale, -m12 * scale, -m12 * scale, m11 * scale;
  return k;
}

// h^2 (T^T Q T) - v v^T, v = T^T Q n: the matrix curvature_tensor inverts,
// times h^2 (no division), as its three entries {m11, m12, m22}.
inline std::array<double, 3> scaled_tangent_form(const SymMat3& q, const Eigen::Vector3d& qn, double h2,
                                                 const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  std::array<double, 3> m;
  pw85_kernel::scaled_tangent_form(q.data(), qn.data(), h2, t1.data(), t2.data(), m.data());
  return m;
}

// R* = 1/sqrt(det(K_i + K_j)) of two ellipsoids at their support points of
// normals +n and -n (qn = Q n, h2 = n^T Q n, h = sqrt(h2) for each), with
// one division and one square root. With K = h m^{-1} (curvature_tensor) and
// M = h^2 m (scaled_tangent_form), det(X + Y) = det X + det Y + X00 Y11 +
// X11 Y00 - 2 X01 Y01 for symmetric 2x2 X, Y gives
//     R*^2 = det M_i det M_j / (h_i^6 det M_j + h_j^6 det M_i + h_i^3 h_j^3 c),
//     c = Mi11 Mj00 + Mi00 Mj11 - 2 Mi01 Mj01,
// every term positive for convex bodies (c is the mixed discriminant of two
// positive-definite matrices). The same value as
// hertz_radius(curvature_tensor(i) + curvature_tensor(j)) (tested).
inline double hertz_radius_of_pair(const SymMat3& qi, const Eigen::Vector3d& qin, double hi2, double hi,
                                   const SymMat3& qj, const Eigen::Vector3d& qjn, double hj2, double hj,
                                   const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  return pw85_kernel::hertz_radius_of_pair(qi.data(), qin.data(), hi2, hi, qj.data(), qjn.data(), hj2, hj,
                                           t1.data(), t2.data());
}

// The same from the normal alone.
inline Eigen::Matrix2d curvature_tensor(const SymMat3& q, const Eigen::Vector3d& n,
                                        const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) {
  const Eigen::Vector3d qn = form_times(q, n);
  const double h2 = n.dot(qn);
  return curvature_tensor(q, qn, h2, std::sqrt(h2), t1, t2);
}

// R* = 1/sqrt(det K) for the summed curvature tensor K. Principal curvatures
// below `floor` (a conforming or concave pairing, e.g. an ellipsoid flank in a
// cylinder of nearly the same curvature) are raised to it so R* stays finite.
inline double hertz_radius(const Eigen::Matrix2d& k, double floor = 0.0) {
  const double det = k(0, 0) * k(1, 1) - k(0, 1) * k(0, 1);
  // Both principal curvatures positive (trace and determinant > 0) and no
  // floor to apply: R* = 1/sqrt(det K) without the eigenvalues.
  if (floor <= 0.0 && det > 0.0 && k(0, 0) + k(1, 1) > 0.0) return 1.0 / std::sqrt(det);
  const double m = 0.5 * (k(0, 0) + k(1, 1));
  const double r = std::hypot(0.5 * (k(0, 0) - k(1, 1)), k(0, 1));
  double k1 = m + r;
  double k2 = k1 > 0.0 ? (k(0, 0) * k(1, 1) - k(0, 1) * k(0, 1)) / k1 : m - r;
  k1 = std::max(k1, floor);
  k2 = std::max(k2, floor);
  return 1.0 / std::sqrt(k1 * k2);
}

}  // namespace grains::contact
