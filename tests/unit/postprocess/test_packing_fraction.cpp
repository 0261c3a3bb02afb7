#include <gtest/gtest.h>

#include <random>

#include "postprocess/packing_fraction.hpp"

namespace grains::postprocess {
namespace {

TEST(PackingFraction, SphereBoxVolumeClosedForms) {
  const double r = 0.7, V = 4.0 / 3.0 * M_PI * r * r * r;
  const Box big{Vec3(-1, -1, -1), Vec3(1, 1, 1)};
  EXPECT_NEAR(sphere_box_volume(Vec3(0, 0, 0), r, big), V, 1e-14);
  EXPECT_NEAR(sphere_box_volume(Vec3(0, 0, 0), r, Box{Vec3(0, -1, -1), Vec3(1, 1, 1)}), V / 2, 1e-12);
  EXPECT_NEAR(sphere_box_volume(Vec3(0, 0, 0), r, Box{Vec3(0, 0, -1), Vec3(1, 1, 1)}), V / 4, 1e-12);
  EXPECT_NEAR(sphere_box_volume(Vec3(0, 0, 0), r, Box{Vec3(0, 0, 0), Vec3(1, 1, 1)}), V / 8, 1e-12);
  // A spherical cap of height h: pi h^2 (3r - h) / 3.
  const double h = 0.2;
  EXPECT_NEAR(sphere_box_volume(Vec3(0, 0, 0), r, Box{Vec3(-1, -1, r - h), Vec3(1, 1, 1)}),
              M_PI * h * h * (3 * r - h) / 3, 1e-12);
  EXPECT_EQ(sphere_box_volume(Vec3(5, 0, 0), r, big), 0.0);
}

TEST(PackingFraction, AgreesWithMonteCarloOnRandomCuts) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int t = 0; t < 20; ++t) {
    const Vec3 c(0.5 * u(rng), 0.5 * u(rng), 0.5 * u(rng));
    const double r = 0.3 + 0.2 * std::abs(u(rng));
    const Box b{Vec3(0.4 * u(rng) - 0.3, 0.4 * u(rng) - 0.3, 0.4 * u(rng) - 0.3), Vec3(0.3, 0.25, 0.35)};
    const int n = 400000;
    int in = 0;
    for (int k = 0; k < n; ++k) {
      const Vec3 p = c + r * Vec3(u(rng), u(rng), u(rng));
      if ((p - c).squaredNorm() <= r * r && (p.array() >= b.lo.array()).all() && (p.array() <= b.hi.array()).all()) ++in;
    }
    const double cube = 8 * r * r * r;
    const double mc = cube * in / n;
    const double sigma = cube * std::sqrt(static_cast<double>(in) / n * (1.0 - static_cast<double>(in) / n) / n);
    EXPECT_NEAR(sphere_box_volume(c, r, b), mc, 4 * sigma + 1e-12) << "trial " << t;
  }
}

TEST(PackingFraction, LatticeOfSpheres) {
  // Simple cubic lattice, spacing 2r: phi = pi/6 in any box aligned with whole cells.
  std::vector<Vec3> x;
  std::vector<double> r;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) {
        x.emplace_back(2 * i + 1, 2 * j + 1, 2 * k + 1);
        r.push_back(1.0);
      }
  EXPECT_NEAR(packing_fraction(x, r, Box{Vec3(2, 2, 2), Vec3(10, 10, 10)}), M_PI / 6, 1e-12);
  // Cut through sphere centres: still pi/6 by symmetry.
  EXPECT_NEAR(packing_fraction(x, r, Box{Vec3(1, 1, 1), Vec3(11, 11, 11)}), M_PI / 6, 1e-12);
}

}  // namespace
}  // namespace grains::postprocess
