// Packing fraction of frames: the exact sphere path, the Monte Carlo union
// volume for ellipsoids and clump balls (checked against closed forms within
// its stated error bar), profiles, and the automatic bulk region.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "postprocess/frame_packing.hpp"

namespace grains::postprocess {
namespace {

Frame random_spheres(int n, double box, double r, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, box);
  Frame f;
  for (int i = 0; i < n; ++i) {
    f.x.emplace_back(u(rng), u(rng), u(rng));
    f.radius.push_back(r);
  }
  return f;
}

TEST(FramePacking, SamplingAgreesWithExactForSeparatedSpheres) {
  // Non-overlapping spheres on a jittered lattice, cut by the region's faces.
  Frame f;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> j(-0.1, 0.1);
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 8; ++k)
      for (int l = 0; l < 8; ++l) {
        f.x.emplace_back(i + j(rng), k + j(rng), l + j(rng));
        f.radius.push_back(0.38);
      }
  const Box region{Vec3(1.3, 0.7, 2.1), Vec3(6.2, 5.9, 5.4)};
  const auto exact = packing_fraction(f, region);
  ASSERT_TRUE(exact.exact);
  // Same frame through the sampler (semi_axes turn the exact path off).
  Frame e = f;
  for (double r : f.radius) e.semi_axes.emplace_back(r, r, r);
  SamplingOptions o;
  o.samples_per_particle = 4000;
  const auto mc = packing_fraction(e, region, o);
  ASSERT_FALSE(mc.exact);
  EXPECT_GT(mc.error, 0.0);
  EXPECT_LT(mc.error, 2e-3);
  EXPECT_NEAR(mc.phi, exact.phi, 4 * mc.error);
}

TEST(FramePacking, OverlappingBallsCountOnce) {
  // Two balls of a clump (radius 1, centres 1 apart) inside a big box: the
  // union volume is 2V - lens, lens = pi (2R - d)^2 (d^2 + 4 d R) / (12 d).
  Frame f;
  f.x = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  f.radius = {1, 1};
  f.body = {3, 3};
  const double R = 1, d = 1, V = 4.0 / 3.0 * M_PI;
  const double lens = M_PI * (2 * R - d) * (2 * R - d) * (d * d + 4 * d * R) / (12 * d);
  const Box box{Vec3(-2, -2, -2), Vec3(3, 2, 2)};
  SamplingOptions o;
  o.samples_per_particle = 200000;
  const auto est = union_volume_in_boxes(f, {box}, o);
  EXPECT_NEAR(est[0].volume, 2 * V - lens, 4 * est[0].error);
  EXPECT_LT(est[0].error, 0.005);
  // The exact sphere path would count the lens twice; the frame has `body`, so it is not used.
  EXPECT_FALSE(exact_spheres(f));
  // Half-space cut through the middle: half the union by symmetry.
  const Box half{Vec3(-2, -2, -2), Vec3(0.5, 2, 2)};
  const auto h = union_volume_in_boxes(f, {half}, o);
  EXPECT_NEAR(h[0].volume, 0.5 * (2 * V - lens), 4 * h[0].error);
}

TEST(FramePacking, EllipsoidVolumeAndRotation) {
  // One ellipsoid (3, 1, 0.5) turned 90 degrees about z, so its long axis is y;
  // a box that keeps y > 0 holds exactly half of it, and one keeping x > 0.5
  // holds the cap beyond x = 0.5 of the short (1) axis now along x.
  Frame f;
  f.x = {Vec3(0, 0, 0)};
  f.radius = {3};
  f.semi_axes = {Vec3(3, 1, 0.5)};
  f.orientation = {Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()))};
  const double V = 4.0 / 3.0 * M_PI * 3 * 1 * 0.5;
  SamplingOptions o;
  o.samples_per_particle = 100000;
  const auto all = union_volume_in_boxes(f, {Box{Vec3::Constant(-4), Vec3::Constant(4)}}, o);
  EXPECT_DOUBLE_EQ(all[0].volume, V);  // whole and alone: exact
  EXPECT_EQ(all[0].error, 0.0);
  const auto parts = union_volume_in_boxes(
      f, {Box{Vec3(-4, 0, -4), Vec3(4, 4, 4)}, Box{Vec3(0.5, -4, -4), Vec3(4, 4, 4)}}, o);
  EXPECT_NEAR(parts[0].volume, V / 2, 4 * parts[0].error);
  // Cap of an ellipsoid beyond x = h along a semi-axis a: V * (1 - h/a)^2 (2 + h/a) / 4.
  const double t = 0.5;
  EXPECT_NEAR(parts[1].volume, V * (1 - t) * (1 - t) * (2 + t) / 4, 4 * parts[1].error);
  EXPECT_GT(parts[1].error, 0.0);
}

TEST(FramePacking, ExactProfileOfALatticeIsFlat) {
  // Simple cubic, spacing 2, radius 1: slabs of one cell have phi = pi/6.
  Frame f;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k) {
        f.x.emplace_back(2 * i + 1, 2 * j + 1, 2 * k + 1);
        f.radius.push_back(1);
      }
  const auto p = phi_profile(f, Box{Vec3(0, 0, 0), Vec3(10, 10, 10)}, 2, 2.0);
  ASSERT_EQ(p.phi.size(), 5u);
  EXPECT_TRUE(p.exact);
  for (double v : p.phi) EXPECT_NEAR(v, M_PI / 6, 1e-12);
  // Half-cell slabs along x: still pi/6 by symmetry of each sphere.
  const auto q = phi_profile(f, Box{Vec3(0, 0, 0), Vec3(10, 10, 10)}, 0, 1.0);
  ASSERT_EQ(q.phi.size(), 10u);
  for (double v : q.phi) EXPECT_NEAR(v, M_PI / 6, 1e-12);
}

TEST(FramePacking, AutoBulkRegionStaysInsideTheBed) {
  const Frame f = random_spheres(4000, 20, 0.5, 9);
  const Box b = auto_bulk_region(f, 2.0);
  const Box bounds = particle_bounds(f);
  EXPECT_NEAR(b.lo.x(), bounds.lo.x() + 2.0, 1e-9);
  EXPECT_NEAR(b.hi.y(), bounds.hi.y() - 2.0, 1e-9);
  EXPECT_LT(b.hi.z(), bounds.hi.z() - 2.0);  // below the free surface estimate
  EXPECT_GT(b.hi.z(), b.lo.z());
  EXPECT_THROW(auto_bulk_region(f, 12.0), std::runtime_error);  // margins eat the whole bed
}

}  // namespace
}  // namespace grains::postprocess
