// RDF of perfect lattices: peaks at the lattice's neighbour shells, g -> 0
// inside the first shell, and the shell counts integrate to the coordination.
#include <gtest/gtest.h>

#include <cmath>

#include "postprocess/rdf.hpp"

namespace grains::postprocess {
namespace {

std::vector<Vec3> simple_cubic(int n, double a) {
  std::vector<Vec3> x;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) x.emplace_back(a * i, a * j, a * k);
  return x;
}

std::vector<Vec3> fcc(int n, double a) {
  std::vector<Vec3> x;
  const Vec3 basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& b : basis) x.push_back(a * (Vec3(i, j, k) + b));
  return x;
}

// Number of partners per reference particle within [r0, r1) from g.
double shell_count(const Rdf& g, double r0, double r1) {
  double c = 0;
  for (std::size_t k = 0; k < g.g.size(); ++k) {
    const double a = g.r[k] - 0.5 * g.bin, b = a + g.bin;
    if (a >= r0 && b <= r1) c += g.g[k] * g.density * 4.0 / 3.0 * M_PI * (b * b * b - a * a * a);
  }
  return c;
}

TEST(Rdf, SimpleCubicPeaksAtNeighbourShells) {
  const double a = 1.0;
  const auto x = simple_cubic(16, a);
  // Region = the lattice's cells (density exactly 1/a^3).
  const Box region{Vec3::Constant(-0.5 * a), Vec3::Constant(15.5 * a)};
  const auto g = radial_distribution(x, region, 2.6 * a, 260);
  const auto peaks = rdf_peaks(g, 1.0);
  const double expect[] = {1.0, std::sqrt(2.0), std::sqrt(3.0), 2.0, std::sqrt(5.0), std::sqrt(6.0)};
  ASSERT_GE(peaks.size(), 6u);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(peaks[static_cast<std::size_t>(k)], expect[k] * a, g.bin) << "shell " << k;
  // Nothing inside the first shell; shell populations 6, 12, 8, 6.
  EXPECT_EQ(shell_count(g, 0, 0.95 * a), 0.0);
  EXPECT_NEAR(shell_count(g, 0.95, 1.05), 6.0, 1e-9);
  EXPECT_NEAR(shell_count(g, 1.36, 1.46), 12.0, 1e-9);
  EXPECT_NEAR(shell_count(g, 1.68, 1.78), 8.0, 1e-9);
  EXPECT_NEAR(shell_count(g, 1.95, 2.05), 6.0, 1e-9);
}

TEST(Rdf, FccFirstShellOfTwelveAtContactDistance) {
  const double a = 2.0, d = a / std::sqrt(2.0);  // touching spheres of diameter d
  const auto x = fcc(10, a);
  const Box region{Vec3::Constant(-0.25 * a), Vec3::Constant(9.75 * a)};
  const auto g = radial_distribution(x, region, 2.2 * d, 220);
  const auto peaks = rdf_peaks(g, 1.0);
  ASSERT_GE(peaks.size(), 3u);
  EXPECT_NEAR(peaks[0], d, g.bin);
  EXPECT_NEAR(peaks[1], a, g.bin);                     // second shell at the cube edge (6 partners)
  EXPECT_NEAR(peaks[2], std::sqrt(1.5) * a, g.bin);    // third shell (24 partners)
  EXPECT_NEAR(shell_count(g, 0.95 * d, 1.05 * d), 12.0, 1e-9);
}

TEST(Rdf, IdealGasIsFlat) {
  // Uniform random points: g = 1 within statistical noise at every r.
  std::vector<Vec3> x;
  std::uint64_t s = 88172645463325252ull;
  auto next = [&] {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return static_cast<double>(s >> 11) / 9007199254740992.0;
  };
  for (int i = 0; i < 40000; ++i) x.emplace_back(20 * next(), 20 * next(), 20 * next());
  const Box region{Vec3::Zero(), Vec3::Constant(20)};
  const auto g = radial_distribution(x, region, 3.0, 10);
  for (std::size_t k = 3; k < g.g.size(); ++k) EXPECT_NEAR(g.g[k], 1.0, 0.05) << "r = " << g.r[k];
}

TEST(Rdf, RegionTooSmallForRmaxIsAnError) {
  const auto x = simple_cubic(4, 1.0);
  EXPECT_THROW(radial_distribution(x, Box{Vec3::Zero(), Vec3::Constant(3)}, 2.0, 10), std::invalid_argument);
}

}  // namespace
}  // namespace grains::postprocess
