#pragma once
// Keeping orientations orthonormal under round-off (seed 003, "Gram-Schmidt
// orthogonalization"). An integrator that accumulates rotation matrices or
// quaternions drifts away from SO(3) by ~1e-16 per step; these helpers pull it
// back. Cost: a few tens of flops; apply every step or every few steps.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace grains::contact {

// Modified Gram-Schmidt on the columns of R: column 0 keeps its direction,
// column 1 loses its component along column 0, and column 2 is rebuilt as
// col0 x col1 so the result is a proper rotation (det = +1) even when the
// input had drifted towards a reflection. Modified (not classical) GS: each
// projection uses the already-orthogonalised vectors, which keeps the error
// at O(eps) for nearly orthonormal input.
inline void orthonormalize(Eigen::Matrix3d& R) {
  Eigen::Vector3d a = R.col(0), b = R.col(1);
  a /= a.norm();
  b -= a.dot(b) * a;
  b /= b.norm();
  b -= a.dot(b) * a;  // second pass ("twice is enough", Kahan-Parlett)
  b /= b.norm();
  R.col(0) = a;
  R.col(1) = b;
  R.col(2) = a.cross(b);
}

// Renormalise a quaternion; for |q| = 1 + d with small d the one-step Newton
// update q (3 - |q|^2) / 2 matches dividing by the norm to rounding
// when |d| < 1e-8, and is cheaper.
inline void renormalize(Eigen::Quaterniond& q) {
  const double n2 = q.squaredNorm();
  if (std::abs(n2 - 1.0) < 1e-8)  // error 3 d^2 / 8 < 4e-17
    q.coeffs() *= 0.5 * (3.0 - n2);
  else
    q.coeffs() /= std::sqrt(n2);
}

}  // namespace grains::contact
