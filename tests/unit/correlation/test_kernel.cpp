// The spreading kernel's pieces: quadrature, the prolate spheroidal wave
// function, parameter choice, polynomial fit and the kernel's Fourier transform.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/correlation/spreading_kernel.hpp"
#include "contact/correlation/fftw_util.hpp"
#include "contact/correlation/gauss_legendre.hpp"

namespace gc = grains::correlation;

TEST(GaussLegendre, IntegratesPolynomialsAndCosine) {
  for (int q : {1, 2, 5, 12, 40}) {
    const auto r = gc::gauss_legendre(q);
    double s0 = 0, s2 = 0, sc = 0;
    for (int i = 0; i < q; ++i) {
      s0 += r.weights[i];
      s2 += r.weights[i] * std::pow(r.nodes[i], 2 * q - 2);
      sc += r.weights[i] * std::cos(3.0 * r.nodes[i]);
    }
    EXPECT_NEAR(s0, 2.0, 1e-14);
    EXPECT_NEAR(s2, 2.0 / (2 * q - 1), 1e-14) << q;
    if (q >= 12) {
      EXPECT_NEAR(sc, 2.0 * std::sin(3.0) / 3.0, 1e-14);
    }
  }
}

TEST(SpreadingKernel, WidthGrowsAsToleranceShrinks) {
  int prev = 0;
  for (double eps = 1e-2; eps >= 1e-12; eps /= 10) {
    const auto k = gc::choose_kernel(eps, 2.0);
    EXPECT_GE(k.width, prev);
    EXPECT_LE(k.width, gc::kMaxKernelWidth);
    prev = k.width;
  }
  EXPECT_THROW(gc::choose_kernel(1e-12, 1.25), std::invalid_argument);
  EXPECT_THROW(gc::choose_kernel(0.5, 2.0), std::invalid_argument);
  EXPECT_NO_THROW(gc::choose_kernel(1e-9, 1.25));
  EXPECT_THROW(gc::choose_kernel(1e-10, 1.25), std::invalid_argument);
  // The widths the PSWF needs at upsampling 2 (docs/nfft.md): one node less
  // than the exponential of semicircle's up to eps = 1e-8.
  EXPECT_EQ(gc::choose_kernel(1e-3, 2.0).width, 4);
  EXPECT_EQ(gc::choose_kernel(1e-6, 2.0).width, 7);
}

TEST(SpreadingKernel, PolynomialMatchesExactKernel) {
  for (double eps : {1e-2, 1e-6, 1e-12}) {
    const auto spec = gc::choose_kernel(eps, 2.0);
    const auto kp = gc::fit_kernel_polynomial(spec);
    const gc::KernelFunction phi(spec);
    double out[gc::kMaxKernelWidth];
    double worst = 0.0;
    for (int s = 0; s <= 200; ++s) {
      const double v = s / 200.0 * (1.0 - 1e-12);
      gc::eval_kernel_polynomial(kp, v, out);
      for (int i = 0; i < spec.width; ++i) {
        const double t = v - 0.5 * spec.width + i;
        worst = std::max(worst, std::abs(out[i] - phi(2.0 * t / spec.width)));
      }
    }
    EXPECT_LT(worst, 0.05 * eps) << "eps " << eps;
  }
}

TEST(SpreadingKernel, FourierSeriesMatchesRiemannSum) {
  // psi_hat(k) = int psi(t) cos(2 pi k t / n) dt; compare with a fine
  // midpoint rule.
  const auto spec = gc::choose_kernel(1e-6, 2.0);
  const int n = 64;
  const auto ph = gc::kernel_fourier_series(spec, n, 20);
  const gc::KernelFunction phi(spec);
  for (int k : {0, 7, 20}) {
    const int q = 400000;
    double s = 0.0;
    const double a = -0.5 * spec.width, h = spec.width / static_cast<double>(q);
    for (int i = 0; i < q; ++i) {
      const double t = a + (i + 0.5) * h;
      s += phi(2.0 * t / spec.width) *
           std::cos(2.0 * std::numbers::pi * k * t / n) * h;
    }
    EXPECT_NEAR(ph[k], s, 1e-9 * ph[0]) << k;
  }
}

TEST(SpreadingKernel, IsAnEigenfunctionOfTheFiniteFourierTransform) {
  // psi_0(c, .) satisfies  int_{-1}^{1} exp(i c x t) psi_0(t) dt = lambda psi_0(x)
  // for |x| <= 1 (Slepian and Pollak): an independent check of the Legendre
  // eigenvector. The integral (real: psi_0 is even) by a 200-point
  // Gauss–Legendre rule, exact to rounding for this entire integrand.
  for (double eps : {1e-3, 1e-6, 1e-12}) {
    const auto spec = gc::choose_kernel(eps, 2.0);
    const gc::KernelFunction phi(spec);
    const auto rule = gc::gauss_legendre(200);
    auto finite_ft = [&](double x) {
      double s = 0.0;
      for (std::size_t j = 0; j < rule.nodes.size(); ++j)
        s += rule.weights[j] * std::cos(spec.beta * x * rule.nodes[j]) * phi(rule.nodes[j]);
      return s;
    };
    const double lambda = finite_ft(0.0);  // phi(0) = 1
    EXPECT_DOUBLE_EQ(phi(0.0), 1.0);
    for (double x : {0.1, 0.37, 0.5, 0.8, 0.95, 0.999}) {
      EXPECT_NEAR(finite_ft(x) / lambda, phi(x), 1e-12) << "eps " << eps << " x " << x;
      EXPECT_DOUBLE_EQ(phi(-x), phi(x));
    }
    // Half-open support: the left end keeps the limit value (the PSWF does
    // not vanish there), the right end is outside.
    EXPECT_GT(phi(-1.0), 0.0);
    EXPECT_NEAR(phi(-1.0), finite_ft(1.0) / lambda, 1e-12);
    EXPECT_EQ(phi(1.0), 0.0);
    EXPECT_EQ(phi(-1.5), 0.0);
  }
}

TEST(FftSize, SmoothEvenSizes) {
  EXPECT_EQ(gc::next_fft_size(1), 2);
  EXPECT_EQ(gc::next_fft_size(31), 32);
  EXPECT_EQ(gc::next_fft_size(33), 36);
  EXPECT_EQ(gc::next_fft_size(61), 64);
  EXPECT_EQ(gc::next_fft_size(97), 100);
  EXPECT_EQ(gc::next_fft_size(121), 128);
}
