#pragma once
// An ellipsoid as a DEM body sees it (centre, semi-axes, orientation) and its
// quadratic form Q in the PW85 convention of the seed document
// (shared/seeds/000): the body is { m : (m-c)^T Q^{-1} (m-c) <= 1 } with
//
//     Q = R diag(a0^2, a1^2, a2^2) R^T = sum_i a_i^2 v_i v_i^T,
//
// i.e. Q is the *inverse* of the usual "x^T A x <= 1" matrix, it has units of
// length^2, and its support function is h(n) = sqrt(n^T Q n). The columns v_i of
// R are the body axes in the world frame (R maps body to world coordinates).
// Q is passed around as its upper triangle in row-major order, exactly as the
// pw85 library and the `grains pw85` CSV do:
//     q = {Q00, Q01, Q02, Q11, Q12, Q22}.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

namespace grains::contact {

using SymMat3 = std::array<double, 6>;  // {Q00, Q01, Q02, Q11, Q12, Q22}
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// Q = R diag(a^2) R^T from semi-axes a (body frame) and a rotation matrix R
// (body -> world; R must be orthonormal).
inline SymMat3 quadratic_form(const Eigen::Vector3d& semi_axes, const Mat3& R) {
  const Eigen::Vector3d a2 = semi_axes.cwiseProduct(semi_axes);
  SymMat3 q{};
  int k = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j)
      q[k++] = R(i, 0) * a2[0] * R(j, 0) + R(i, 1) * a2[1] * R(j, 1) + R(i, 2) * a2[2] * R(j, 2);
  return q;
}

// Same from a unit quaternion (body -> world).
inline SymMat3 quadratic_form(const Eigen::Vector3d& semi_axes, const Quat& orientation) {
  return quadratic_form(semi_axes, orientation.toRotationMatrix());
}

// Full symmetric 3x3 matrix from the packed upper triangle, and back.
inline Mat3 to_matrix(const SymMat3& q) {
  Mat3 m;
  m << q[0], q[1], q[2], q[1], q[3], q[4], q[2], q[4], q[5];
  return m;
}
inline SymMat3 to_packed(const Mat3& m) {
  return {m(0, 0), 0.5 * (m(0, 1) + m(1, 0)), 0.5 * (m(0, 2) + m(2, 0)),
          m(1, 1), 0.5 * (m(1, 2) + m(2, 1)), m(2, 2)};
}

// Q n for packed Q.
inline Eigen::Vector3d form_times(const SymMat3& q, const Eigen::Vector3d& n) {
  return {q[0] * n[0] + q[1] * n[1] + q[2] * n[2], q[1] * n[0] + q[3] * n[1] + q[4] * n[2],
          q[2] * n[0] + q[4] * n[1] + q[5] * n[2]};
}

// Support function h(n) = max_{m in E} (m - c).n = sqrt(n^T Q n) for unit n.
inline double support(const SymMat3& q, const Eigen::Vector3d& n) {
  return std::sqrt(n.dot(form_times(q, n)));
}

// A DEM ellipsoid. `orientation` maps body to world frame; body axis i has
// semi-axis semi_axes[i].
struct Ellipsoid {
  Eigen::Vector3d centre{0, 0, 0};
  Eigen::Vector3d semi_axes{1, 1, 1};
  Quat orientation = Quat::Identity();

  SymMat3 form() const { return quadratic_form(semi_axes, orientation); }
};

}  // namespace grains::contact
