#pragma once
// Closed forms for balls: the Fourier transform of a ball's indicator, the
// volume of the lens where two balls intersect, and a ball's indicator
// smoothed by an isotropic Gaussian. They are the radial kernels of the
// seed's Section 3 (correlations = knot densities convolved with kernels) and
// the exact references of the tests.
#include <algorithm>
#include <cmath>
#include <numbers>

namespace grains::correlation {

// int_{|x|<r} e^{-i k.x} dx = 4 pi (sin kr - kr cos kr) / k^3, at |k| = k.
// Series near k r = 0, where the closed form cancels catastrophically.
inline double ball_indicator_transform(double k, double r) {
  const double a = k * r;
  const double r3 = r * r * r;
  if (a < 1e-2) {
    const double a2 = a * a;
    // 4 pi r^3 (1/3 - a^2/30 + a^4/840 - a^6/45360)
    return 4.0 * std::numbers::pi * r3 *
           (1.0 / 3.0 - a2 / 30.0 + a2 * a2 / 840.0 - a2 * a2 * a2 / 45360.0);
  }
  return 4.0 * std::numbers::pi * (std::sin(a) - a * std::cos(a)) / (k * k * k);
}

// Volume of B(0, r) intersected with B(d e, s).
inline double lens_volume(double d, double r, double s) {
  d = std::abs(d);
  if (d >= r + s) return 0.0;
  const double small = std::min(r, s);
  if (d <= std::abs(r - s)) return 4.0 / 3.0 * std::numbers::pi * small * small * small;
  const double t = r + s - d;
  return std::numbers::pi * t * t * (d * d + 2.0 * d * (r + s) - 3.0 * (r - s) * (r - s)) /
         (12.0 * d);
}

// (1_{B(0,R)} * G_sigma)(x) at |x| = rho, G_sigma the normalised isotropic
// Gaussian of standard deviation sigma per axis: the probability that a
// N(x, sigma^2 I) point lies in the ball (noncentral chi, 3 degrees of freedom):
//   Phi(a-b) + Phi(a+b) - 1 - (1/b) [phi(a-b) - phi(a+b)],  a = R/sigma, b = rho/sigma.
inline double gaussian_smoothed_ball(double rho, double radius, double sigma) {
  const double a = radius / sigma, b = std::abs(rho) / sigma;
  const double inv_sqrt2 = 1.0 / std::numbers::sqrt2;
  const double inv_sqrt2pi = 0.5 * std::numbers::inv_sqrtpi * std::numbers::sqrt2;
  // Phi(a-b) + Phi(a+b) - 1 = (erf((a-b)/sqrt2) + erf((a+b)/sqrt2)) / 2
  const double cdf = 0.5 * (std::erf((a - b) * inv_sqrt2) + std::erf((a + b) * inv_sqrt2));
  double tail;
  if (b < 1.0) {
    // phi(a-b) - phi(a+b) = 2 phi(a) e^{-b^2/2} sinh(ab); sinh(ab)/b is stable.
    const double sinhc = (a * b < 1e-8) ? a : std::sinh(a * b) / b;
    tail = 2.0 * inv_sqrt2pi * std::exp(-0.5 * (a * a + b * b)) * sinhc;
  } else {
    tail = inv_sqrt2pi * (std::exp(-0.5 * (a - b) * (a - b)) - std::exp(-0.5 * (a + b) * (a + b))) / b;
  }
  return cdf - tail;
}

}  // namespace grains::correlation
