// Gram-Schmidt re-orthonormalisation of rotation matrices and quaternion
// renormalisation keep orientations on SO(3) over 10^6 steps.
#include <gtest/gtest.h>

#include <cmath>

#include "contact/ellipsoid/orthonormalize.hpp"
#include "tests/unit/ellipsoid/random_ellipsoids.hpp"

namespace grains::contact {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

double orthonormality_error(const Matrix3d& R) { return (R.transpose() * R - Matrix3d::Identity()).norm(); }

TEST(Orthonormalize, SeedExample) {
  // Seed 003's example: A = [5 9 6; 7 -4 -1; 2 3 -8] gives unit columns along
  // (5,7,2), (587,-473,188) and, up to the sign fixed by right-handedness,
  // (29,3,-83) (the seed's determinant is +1 with its third column).
  Matrix3d A;
  A << 5, 9, 6, 7, -4, -1, 2, 3, -8;
  orthonormalize(A);
  EXPECT_LT(orthonormality_error(A), 1e-15);
  EXPECT_NEAR(A.determinant(), 1.0, 1e-15);
  EXPECT_LT((A.col(0) - Vector3d(5, 7, 2) / std::sqrt(78.0)).norm(), 1e-15);
  EXPECT_LT((A.col(1) - Vector3d(587, -473, 188) / std::sqrt(603642.0)).norm(), 1e-15);
  EXPECT_LT((A.col(2) - Vector3d(29, 3, -83) / std::sqrt(7739.0)).norm(), 1e-15);
}

TEST(Orthonormalize, MillionStepsOfIncrementalRotation) {
  // R <- R * dR with a slightly non-orthogonal increment (as an explicit
  // integrator produces): without correction the error grows linearly,
  // with Gram-Schmidt each step it stays at rounding level.
  test::Rng rng(50);
  Matrix3d dR = Eigen::AngleAxisd(1e-3, rng.unit_vector()).toRotationMatrix();
  dR += 1e-12 * Matrix3d::Random();
  Matrix3d R = Matrix3d::Identity(), raw = Matrix3d::Identity();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  const Eigen::Quaterniond dq(Eigen::AngleAxisd(1e-3, rng.unit_vector()));
  double worst = 0, worst_q = 0;
  for (int step = 0; step < 1000000; ++step) {
    R = R * dR;
    orthonormalize(R);
    q = q * dq;
    q.coeffs() *= 1 + 1e-13;  // drift
    renormalize(q);
    if (step < 1000) raw = raw * dR;
    if (step % 1000 == 0) {
      worst = std::max(worst, orthonormality_error(R));
      worst_q = std::max(worst_q, std::abs(q.norm() - 1));
    }
  }
  std::cout << "after 1e6 steps: |R^T R - I| <= " << worst << ", ||q| - 1| <= " << worst_q
            << "; uncorrected after 1e3 steps " << orthonormality_error(raw) << "\n";
  EXPECT_LT(worst, 1e-14);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
  EXPECT_LT(worst_q, 1e-15);
  EXPECT_GT(orthonormality_error(raw), 1e-10);
}

}  // namespace
}  // namespace grains::contact
