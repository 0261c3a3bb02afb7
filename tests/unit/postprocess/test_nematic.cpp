// Nematic order parameter: S = 1 for aligned axes, ~0 for isotropic ones,
// 1/4 for axes spread in a plane; director and axis choice.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "postprocess/nematic_order.hpp"

namespace grains::postprocess {
namespace {

TEST(Nematic, AlignedAxesGiveOne) {
  // Parallel and antiparallel axes are the same axis.
  const Vec3 d = Vec3(1, 2, -2).normalized();
  std::vector<Vec3> u;
  for (int i = 0; i < 100; ++i) u.push_back(i % 2 ? d : Vec3(-d));
  const auto r = nematic_order(u);
  EXPECT_NEAR(r.S, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(r.director.dot(d)), 1.0, 1e-12);
  EXPECT_NEAR(r.eigenvalues[0], -0.5, 1e-12);
}

TEST(Nematic, IsotropicAxesGiveNearlyZero) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  std::vector<Vec3> u(20000);
  for (auto& v : u) v = Vec3(g(rng), g(rng), g(rng));
  const auto r = nematic_order(u);
  EXPECT_LT(r.S, 0.03);
  EXPECT_GT(r.S, 0.0);  // the largest eigenvalue of a finite sample is positive
  // Consistent with the finite-N baseline (both O(1/sqrt N)).
  EXPECT_LT(r.S, 3 * r.isotropic_baseline);
  EXPECT_LT(r.isotropic_baseline, 0.03);
}

TEST(Nematic, PlanarAxesGiveOneQuarter) {
  std::vector<Vec3> u;
  for (int k = 0; k < 360; ++k) u.emplace_back(std::cos(k * M_PI / 180), std::sin(k * M_PI / 180), 0);
  const auto r = nematic_order(u);
  EXPECT_NEAR(r.S, 0.25, 1e-12);
  EXPECT_NEAR(r.eigenvalues[0], -0.5, 1e-12);
}

TEST(Nematic, FrameUsesOrientationAndShapeAxis) {
  // Prolate spheroids (long body axis x) all rotated so that x points along z:
  // S = 1 and the director is z. Oblate ones (short axis z) rotated the same
  // way have their symmetry axis (body z) along world x.
  const Quat q(Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitY()));  // body x -> world z
  Frame f;
  for (int i = 0; i < 50; ++i) {
    f.x.emplace_back(i, 0, 0);
    f.radius.push_back(1);
    f.orientation.push_back(q);
    f.semi_axes.emplace_back(2, 1, 1);
  }
  const Box all{Vec3::Constant(-100), Vec3::Constant(100)};
  auto r = nematic_order(f, all);
  EXPECT_EQ(r.axis, 0);
  EXPECT_NEAR(r.S, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(r.director.z()), 1.0, 1e-12);
  for (auto& a : f.semi_axes) a = Vec3(1, 1, 0.4);
  r = nematic_order(f, all);
  EXPECT_EQ(r.axis, 2);
  EXPECT_NEAR(std::abs(r.director.x()), 1.0, 1e-12);
  // Only particles in the region count; none at all gives n = 0.
  EXPECT_EQ(nematic_order(f, Box{Vec3::Constant(500), Vec3::Constant(600)}).n, 0u);
  // No orientations: an error that names the missing array.
  f.orientation.clear();
  EXPECT_THROW(nematic_order(f, all), std::runtime_error);
}

TEST(Nematic, ShapeAxisPicksTheSymmetryAxis) {
  EXPECT_EQ(shape_axis(Vec3(1, 3, 1)), 1);     // prolate along y
  EXPECT_EQ(shape_axis(Vec3(2, 2, 0.5)), 2);   // oblate, short z
  EXPECT_EQ(shape_axis(Vec3(1.25, 1, 0.8)), 0);  // triaxial: the farthest from the others' mean
}

}  // namespace
}  // namespace grains::postprocess
