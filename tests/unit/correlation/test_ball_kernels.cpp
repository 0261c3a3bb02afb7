// Closed forms for balls against numerical integration.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/correlation/ball_kernels.hpp"

namespace gc = grains::correlation;
constexpr double kPi = std::numbers::pi;

TEST(BallKernels, IndicatorTransformMatchesRadialIntegral) {
  // int_{|x|<r} e^{-ik.x} dx = int_0^r 4 pi s^2 sin(ks)/(ks) ds.
  for (double k : {1e-6, 0.5, 3.0, 40.0}) {
    const double r = 0.7;
    const int q = 20000;
    double s = 0.0;
    for (int i = 0; i < q; ++i) {
      const double x = (i + 0.5) * r / q;
      s += 4 * kPi * x * x * std::sin(k * x) / (k * x) * r / q;
    }
    EXPECT_NEAR(gc::ball_indicator_transform(k, r), s, 1e-7 * 4 * kPi * r * r * r / 3) << k;
  }
  // The series and the closed form agree where they hand over.
  const double r = 1.3, k = 1e-2 / r;
  const double closed = 4 * kPi * (std::sin(k * r) - k * r * std::cos(k * r)) / (k * k * k);
  EXPECT_NEAR(gc::ball_indicator_transform(k * (1 - 1e-12), r), closed, 1e-9 * closed);
}

TEST(BallKernels, LensVolumeMatchesQuadrature) {
  const double r = 1.0, s = 0.6;
  EXPECT_DOUBLE_EQ(gc::lens_volume(0.0, r, s), 4.0 / 3.0 * kPi * s * s * s);
  EXPECT_DOUBLE_EQ(gc::lens_volume(1.6, r, s), 0.0);
  EXPECT_DOUBLE_EQ(gc::lens_volume(0.4, r, s), 4.0 / 3.0 * kPi * s * s * s);
  for (double d : {0.5, 0.9, 1.3, 1.55}) {
    // Slices along the axis: area of intersection of two discs at height z.
    const int q = 200000;
    double v = 0.0;
    const double zlo = d - s, zhi = r;
    for (int i = 0; i < q; ++i) {
      const double z = zlo + (i + 0.5) * (zhi - zlo) / q;
      const double a2 = r * r - z * z, b2 = s * s - (z - d) * (z - d);
      if (a2 > 0 && b2 > 0) v += kPi * std::min(a2, b2) * (zhi - zlo) / q;
    }
    EXPECT_NEAR(gc::lens_volume(d, r, s), v, 1e-6) << d;
    EXPECT_DOUBLE_EQ(gc::lens_volume(d, r, s), gc::lens_volume(d, s, r));
  }
}

TEST(BallKernels, GaussianSmoothedBallMatchesQuadrature) {
  // (1_B * G)(rho e_z) = int_disc G(x) G(y) [Phi((h - rho)/sig) - Phi((-h - rho)/sig)], h = sqrt(R^2 - x^2 - y^2).
  const double R = 1.0;
  for (double sig : {0.1, 0.4}) {
    for (double rho : {0.0, 1e-9, 0.3, 0.95, 1.2, 1.8}) {
      const int q = 600;
      double v = 0.0;
      const double h = 2.0 * R / q;
      auto g = [&](double t) { return std::exp(-0.5 * t * t / (sig * sig)) / (sig * std::sqrt(2 * kPi)); };
      auto Phi = [&](double t) { return 0.5 * std::erfc(-t / (sig * std::sqrt(2.0))); };
      for (int i = 0; i < q; ++i)
        for (int j = 0; j < q; ++j) {
          const double x = -R + (i + 0.5) * h, y = -R + (j + 0.5) * h;
          const double hh = R * R - x * x - y * y;
          if (hh <= 0) continue;
          const double c = std::sqrt(hh);
          v += g(x) * g(y) * (Phi(c - rho) - Phi(-c - rho)) * h * h;
        }
      EXPECT_NEAR(gc::gaussian_smoothed_ball(rho, R, sig), v, 2e-4) << sig << " " << rho;
    }
  }
  EXPECT_NEAR(gc::gaussian_smoothed_ball(0.0, 1.0, 1e-3), 1.0, 1e-12);
  EXPECT_NEAR(gc::gaussian_smoothed_ball(50.0, 1.0, 0.5), 0.0, 1e-12);
}
