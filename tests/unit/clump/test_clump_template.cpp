// Clump templates: body frame at the centre of mass along principal axes,
// mass properties of sphere and cube clumps close to the closed forms.

#include "clump_test_data.hpp"
#include "contact/clump/ball_union.hpp"
#include "contact/clump/clump_template.hpp"
#include "contact/clump/mesh_distance.hpp"

#include <gtest/gtest.h>

#include <numbers>

using namespace grains::clump;

TEST(ClumpTemplate, SphereClumpMatchesTheSolidBall) {
  ClumpOptions opt;
  opt.decomposition.grid = 33;
  opt.density = 2500.0;
  const ClumpTemplate c = build_clump(test_mesh("sphere.off"), opt);
  ASSERT_EQ(c.balls.size(), 1u);
  const double R = c.balls[0].radius;
  const double m = 2500.0 * 4.0 / 3.0 * std::numbers::pi * R * R * R;
  EXPECT_NEAR(c.mass, m, 1e-3 * m);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(c.inertia[a], 0.4 * m * R * R, 2e-3 * 0.4 * m * R * R);
  EXPECT_LT(c.balls[0].center.norm(), 1e-3 * R);
  EXPECT_NEAR(c.axes.determinant(), 1.0, 1e-12);
  // Metadata: eps, counts, measured errors.
  EXPECT_NEAR(c.meta.epsilon, std::sqrt(3.0) * 0.5 / 33, 1e-12);
  EXPECT_EQ(c.meta.n3, 1u);
  EXPECT_LE(c.meta.hausdorff, c.meta.epsilon * (1 + 1e-9));
  EXPECT_NEAR(c.meta.volume_error, (c.volume - c.meta.mesh_volume) / c.meta.mesh_volume, 1e-15);
}

TEST(ClumpTemplate, CubeClumpHasCubicSymmetry) {
  ClumpOptions opt;
  opt.decomposition.grid = 24;
  opt.measure = false;
  const ClumpTemplate c = build_clump(test_mesh("cube.off"), opt);
  // The union is the cube thickened by up to eps: volume between 8 and (2 + 2 eps)^3.
  EXPECT_GT(c.volume, 8.0);
  EXPECT_LT(c.volume, std::pow(2.0 + 2.0 * c.meta.epsilon, 3));
  EXPECT_LT(c.centre_of_mass.norm(), 1e-3);
  // Three nearly equal principal moments (the greedy order breaks ties by node
  // index, so the ball set itself is only nearly symmetric), close to a cube of
  // the same volume: m s^2 / 6.
  const double s = std::cbrt(c.volume);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(c.inertia[a], c.inertia[0], 1e-2 * c.inertia[0]);
    EXPECT_NEAR(c.inertia[a], c.mass * s * s / 6.0, 0.02 * c.mass * s * s / 6.0);
  }
}

TEST(ClumpTemplate, BodyFrameIsPrincipalAtTheCentreOfMass) {
  ClumpOptions opt;
  opt.decomposition.grid = 24;
  opt.measure = false;
  const auto mesh = test_mesh("cow.off");
  const ClumpTemplate c = build_clump(mesh, opt);
  const double finest = opt.integration_cells * 2.0 * 0.5 * (mesh.bbox_max() - mesh.bbox_min()).maxCoeff() / 24;
  const UnionMoments body = union_moments(BallUnion(c.balls), finest);
  const double L = (mesh.bbox_max() - mesh.bbox_min()).maxCoeff();
  EXPECT_LT(body.centroid.norm(), 2e-3 * L);
  const Eigen::Matrix3d I = c.density * body.inertia;
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(I(a, a), c.inertia[a], 0.01 * c.inertia[2]);
  EXPECT_LT(std::abs(I(0, 1)) + std::abs(I(0, 2)) + std::abs(I(1, 2)), 0.01 * c.inertia[2]);
  EXPECT_LE(c.inertia[0], c.inertia[1]);
  EXPECT_LE(c.inertia[1], c.inertia[2]);
  // Mapped back to the mesh frame, each ball is an A3 ball: centre inside the
  // mesh at distance r - eps from its surface.
  const MeshDistance md(mesh);
  for (const Ball& b : c.balls) {
    const Eigen::Vector3d x = c.centre_of_mass + c.axes * b.center;
    EXPECT_NEAR(reference_signed_distance(md, x), -(b.radius - c.meta.epsilon), 1e-9 * L);
  }
}
