// Solid-fraction field: exact integrals and agreement with a direct voxel
// evaluation of the same (Gaussian coarse-grained) field.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/correlation/ball_kernels.hpp"
#include "contact/correlation/solid_fraction.hpp"
#include "scenes.hpp"

namespace gc = grains::correlation;
namespace gt = grains::correlation::testing;
constexpr double kPi = std::numbers::pi;

namespace {

double solid_volume(const gt::Scene& s) {
  double v = 0.0;
  for (double r : s.radii) v += 4.0 / 3.0 * kPi * r * r * r;
  return v;
}

// Direct evaluation at every node: sum over balls and their nearest periodic
// images (offsets -1, 0, 1 periods from the minimum image along periodic
// axes; enough for a Gaussian reach below one period) of the closed-form
// Gaussian-smoothed ball.
std::vector<double> direct_field(const gt::Scene& s, const gc::GridSpec& g, double l) {
  std::vector<double> f(g.num_nodes(), 0.0);
  std::array<double, 3> L;
  for (int d = 0; d < 3; ++d) L[d] = g.dims[d] * g.spacing[d];
  for (std::size_t n = 0; n < f.size(); ++n) {
    const auto x = g.node(n);
    for (std::size_t i = 0; i < s.radii.size(); ++i) {
      double d[3];
      for (int a = 0; a < 3; ++a) {
        d[a] = x[a] - s.centres[3 * i + a];
        if (g.periodic[a]) d[a] -= L[a] * std::round(d[a] / L[a]);
      }
      for (int q2 = -1; q2 <= 1; ++q2)
        for (int q1 = -1; q1 <= 1; ++q1)
          for (int q0 = -1; q0 <= 1; ++q0) {
            const int q[3] = {q0, q1, q2};
            double r2 = 0.0;
            bool skip = false;
            for (int a = 0; a < 3; ++a) {
              if (!g.periodic[a] && q[a] != 0) skip = true;
              const double e = d[a] + q[a] * L[a];
              r2 += e * e;
            }
            if (!skip) f[n] += gc::gaussian_smoothed_ball(std::sqrt(r2), s.radii[i], l);
          }
    }
  }
  return f;
}

gc::GridSpec cube_grid(double L, int n) {
  gc::GridSpec g;
  g.spacing = {L / n, L / n, L / n};
  g.dims = {n, n, n};
  return g;
}

}  // namespace

TEST(SolidFraction, IntegralIsTheSolidVolume) {
  const double L = 1.0;
  const auto s = gt::rsa_scene(L, {0.05, 0.08, 0.11}, 60, 21);
  ASSERT_EQ(s.radii.size(), 60u);
  const gc::BallSet balls{s.centres, s.radii};
  for (double tol : {1e-3, 1e-6, 1e-10}) {
    gc::SolidFractionOptions opt;
    opt.tolerance = tol;
    gc::SolidFractionInfo info;
    const auto f = solid_fraction_field(balls, cube_grid(L, 24), opt, &info);
    EXPECT_EQ(info.radius_classes, 3);
    double sum = 0.0;
    for (double v : f) sum += v;
    const double integral = sum * std::pow(L / 24, 3);
    EXPECT_NEAR(integral, solid_volume(s), tol * solid_volume(s)) << tol;
  }
}

TEST(SolidFraction, AgreesWithDirectVoxelEvaluation) {
  const double L = 2.0;
  const auto s = gt::rsa_scene(L, {0.12, 0.2}, 40, 22);
  const gc::BallSet balls{s.centres, s.radii};
  auto g = cube_grid(L, 20);
  g.origin = {-0.3, 0.1, 0.05};  // nodes need not start at the box corner
  for (double lfac : {0.7, 1.0, 2.5}) {
    const auto ref = direct_field(s, g, lfac * g.spacing[0]);
    for (double tol : {1e-3, 1e-6, 1e-9}) {
      gc::SolidFractionOptions opt;
      opt.tolerance = tol;
      opt.smoothing_length = lfac * g.spacing[0];
      const auto f = solid_fraction_field(balls, g, opt);
      double worst = 0.0;
      for (std::size_t n = 0; n < f.size(); ++n) worst = std::max(worst, std::abs(f[n] - ref[n]));
      EXPECT_LE(worst, tol) << "tol " << tol << " l/h " << lfac;
    }
  }
}

TEST(SolidFraction, PaddedAxesSeeNoPeriodicImages) {
  // Periodic in x and y, walls in z: balls touching the z faces must not
  // leak to the other side.
  const double L = 1.0;
  std::vector<double> c = {0.5, 0.5, 0.04, 0.2, 0.7, 0.96, 0.8, 0.2, 0.5};
  std::vector<double> r = {0.1, 0.1, 0.15};
  gt::Scene s{c, r};
  auto g = cube_grid(L, 20);
  g.periodic = {true, true, false};
  g.dims[2] = 21;  // nodes 0 .. 1 inclusive along z
  gc::SolidFractionOptions opt;
  opt.tolerance = 1e-7;
  gc::SolidFractionInfo info;
  const auto f = solid_fraction_field(gc::BallSet{c, r}, g, opt, &info);
  EXPECT_GT(info.fft_nodes[2], 21);
  const auto ref = direct_field(s, g, g.spacing[0]);
  double worst = 0.0;
  for (std::size_t n = 0; n < f.size(); ++n) worst = std::max(worst, std::abs(f[n] - ref[n]));
  EXPECT_LE(worst, 1e-7);
}

TEST(SolidFraction, MeanOverARegionIsTheSolidFractionThere) {
  // Region [0.25, 0.75)^3 of the unit box; balls either well inside or well
  // outside (6 l from its faces), so the field's integral over the region is
  // the solid volume inside it.
  const double L = 1.0;
  const int n = 64;
  const double h = L / n, l = h;
  gt::Scene s;
  double inside = 0.0;
  for (int k = 0; k < 8; ++k) {  // eight balls around the centre
    const double r = (k % 2) ? 0.04 : 0.035;
    s.centres.insert(s.centres.end(), {0.5 + ((k & 1) ? 0.05 : -0.05), 0.5 + ((k & 2) ? 0.05 : -0.05),
                                       0.5 + ((k & 4) ? 0.05 : -0.05)});
    s.radii.push_back(r);
    inside += 4.0 / 3.0 * kPi * r * r * r;
  }
  const auto all = gt::rsa_scene(L, {0.04, 0.06}, 300, 23);
  for (std::size_t i = 0; i < all.radii.size(); ++i) {
    const double r = all.radii[i];
    bool out = false;
    for (int a = 0; a < 3; ++a) {
      const double x = all.centres[3 * i + a];
      out = out || x + r < 0.25 - 6 * l || x - r > 0.75 + 6 * l;
    }
    if (out) {
      s.centres.insert(s.centres.end(), &all.centres[3 * i], &all.centres[3 * i] + 3);
      s.radii.push_back(r);
    }
  }
  ASSERT_GT(s.radii.size(), 50u);
  gc::SolidFractionOptions opt;
  opt.tolerance = 1e-8;
  opt.smoothing_length = l;
  const auto f = solid_fraction_field(gc::BallSet{s.centres, s.radii}, cube_grid(L, n), opt);
  double sum = 0.0;
  int count = 0;
  for (int i2 = n / 4; i2 < 3 * n / 4; ++i2)
    for (int i1 = n / 4; i1 < 3 * n / 4; ++i1)
      for (int i0 = n / 4; i0 < 3 * n / 4; ++i0) {
        sum += f[(static_cast<std::size_t>(i2) * n + i1) * n + i0];
        ++count;
      }
  const double mean = sum / count;
  EXPECT_NEAR(mean, inside / 0.125, 1e-6 * inside / 0.125);
}

TEST(SolidFraction, RejectsBadInput) {
  std::vector<double> c = {0, 0, 0}, r = {-1.0};
  EXPECT_THROW(solid_fraction_field(gc::BallSet{c, r}, cube_grid(1, 8)), std::invalid_argument);
  std::vector<double> r2 = {0.1, 0.2};
  EXPECT_THROW(solid_fraction_field(gc::BallSet{c, r2}, cube_grid(1, 8)), std::invalid_argument);
  gc::SolidFractionOptions opt;
  opt.smoothing_length = 1e-6;
  std::vector<double> r1 = {0.1};
  EXPECT_THROW(solid_fraction_field(gc::BallSet{c, r1}, cube_grid(1, 8), opt), std::invalid_argument);
}
