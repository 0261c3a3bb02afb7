// Mass properties of unions of balls against closed forms: overlaps are
// counted once, and the stated bound covers the error.

#include "contact/clump/ball_union.hpp"

#include <gtest/gtest.h>

#include <numbers>

using namespace grains::clump;
using std::numbers::pi;

TEST(BallUnion, SingleBall) {
  const double R = 0.7;
  const BallUnion U({{{0.1, -0.2, 0.3}, R}});
  const UnionMoments m = union_moments(U, R / 128);
  const double V = 4.0 / 3.0 * pi * R * R * R;
  EXPECT_NEAR(m.volume, V, m.volume_bound);
  EXPECT_NEAR(m.volume, V, 2e-4 * V);  // midpoint misses cancel: far below the bound
  EXPECT_LT(m.volume_bound, 0.05 * V);
  EXPECT_NEAR((m.centroid - Eigen::Vector3d(0.1, -0.2, 0.3)).norm(), 0.0, 1e-4 * R);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(m.inertia(a, a), 0.4 * V * R * R, 1e-3 * V * R * R);
  EXPECT_NEAR(m.inertia(0, 1), 0.0, 1e-4 * V * R * R);
}

TEST(BallUnion, TwoOverlappingBallsCountTheLensOnce) {
  // Equal balls of radius R at distance d: union = 2 V_ball - lens,
  // lens = pi (4R + d)(2R - d)^2 / 12.
  const double R = 0.5, d = 0.6;
  const BallUnion U({{{-d / 2, 0, 0}, R}, {{d / 2, 0, 0}, R}});
  const UnionMoments m = union_moments(U, R / 128);
  const double ball = 4.0 / 3.0 * pi * R * R * R;
  const double lens = pi * (4 * R + d) * (2 * R - d) * (2 * R - d) / 12.0;
  const double V = 2 * ball - lens;
  EXPECT_NEAR(m.volume, V, m.volume_bound);
  EXPECT_NEAR(m.volume, V, 5e-4 * V);
  EXPECT_GT(std::abs(m.volume - 2 * ball), 100 * std::abs(m.volume - V));  // not the sum of the balls
  EXPECT_NEAR(m.centroid.norm(), 0.0, 1e-4);
  // Symmetry: I_yy = I_zz, and I_xx < I_yy for a shape elongated along x.
  EXPECT_NEAR(m.inertia(1, 1), m.inertia(2, 2), 1e-4 * m.inertia(1, 1));
  EXPECT_LT(m.inertia(0, 0), m.inertia(1, 1));
}

TEST(BallUnion, NestedBallAddsNothing) {
  const BallUnion U({{{0, 0, 0}, 1.0}, {{0.2, 0.1, 0}, 0.3}});
  const BallUnion V({{{0, 0, 0}, 1.0}});
  EXPECT_DOUBLE_EQ(union_moments(U, 1.0 / 64).volume, union_moments(V, 1.0 / 64).volume);
}

TEST(BallUnion, DistanceQueries) {
  const BallUnion U({{{0, 0, 0}, 1.0}, {{3, 0, 0}, 0.5}});
  EXPECT_NEAR(U.signed_distance_bound({2, 0, 0}), 0.5, 1e-15);
  EXPECT_NEAR(U.signed_distance_bound({0, 0, 10}), 9.0, 1e-15);
  EXPECT_NEAR(U.signed_distance_bound({0, 0, 0}), -1.0, 1e-15);
  EXPECT_TRUE(U.contains({3.4, 0, 0}));
  EXPECT_FALSE(U.contains({1.5, 0, 0}));
}
