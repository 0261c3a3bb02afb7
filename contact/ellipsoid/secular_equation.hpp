#pragma once
// The one-dimensional "secular equation" behind the closest point on an
// ellipsoid to a point (seed 003, "shortest distance from point to quadric")
// and the farthest point of an ellipse from a point (ellipsoid in a
// cylinder). Instead of the notes' degree-6 polynomial, whose coefficients
// lose all accuracy for elongated bodies, the Lagrange multiplier s is found
// as the root s >= 0 of
//
//     S(s) = sum_i alpha_i^2 / (s + d_i)^2 = 1,   alpha_i >= 0, d_i >= 0,
//
// which is decreasing on s > 0. h(s) = S(s)^{-1/2} is increasing and concave
// (Cauchy-Schwarz: (sum a^2 u^3)^2 <= (sum a^2 u^2)(sum a^2 u^4), u = 1/(s+d)),
// so Newton's method on h(s) = 1 started left of the root climbs
// monotonically to it with quadratic convergence; for equal d_i (a sphere) it
// is exact from the first bracket. Bracket:
//     max(0, max_i(alpha_i - d_i), |alpha| - max d) <= s <= |alpha|.
// When S(0+) <= 1 (possible only if every alpha_i with d_i = 0 vanishes) the
// answer is the degenerate s = 0 (Eberly's "hard case": a point on a symmetry
// plane inside the body); the caller then completes the point itself.
#include <algorithm>
#include <cmath>

namespace grains::contact {

template <int N>
double secular_root(const double (&alpha)[N], const double (&d)[N], int* iterations = nullptr) {
  double a2 = 0.0, dmax = 0.0, lo = 0.0, s0 = 0.0;
  bool pole_at_zero = false;
  for (int i = 0; i < N; ++i) {
    a2 += alpha[i] * alpha[i];
    dmax = std::max(dmax, d[i]);
    lo = std::max(lo, alpha[i] - d[i]);
    if (d[i] == 0.0 && alpha[i] > 0.0)
      pole_at_zero = true;
    else if (d[i] > 0.0)
      s0 += (alpha[i] / d[i]) * (alpha[i] / d[i]);
  }
  if (iterations) *iterations = 0;
  if (!pole_at_zero && s0 <= 1.0) return 0.0;  // degenerate case (also alpha = 0)
  const double hi = std::sqrt(a2);
  lo = std::max(lo, hi - dmax);
  double s = lo;
  int it = 0;
  for (; it < 100; ++it) {
    double S = 0.0, dS = 0.0;
    for (int i = 0; i < N; ++i) {
      if (alpha[i] == 0.0) continue;
      const double u = alpha[i] / (s + d[i]);
      S += u * u;
      dS += u * u / (s + d[i]);  // -S'/2
    }
    if (!(S > 0.0)) break;
    const double rs = 1.0 / std::sqrt(S);  // h(s)
    // Newton on h(s) = 1: h' = S^{-3/2} (-S'/2) = rs^3 dS.
    const double step = (1.0 - rs) / (rs * rs * rs * dS);
    double next = s + step;
    if (!(next <= hi)) next = hi;
    if (!(next >= lo)) next = lo;
    // Quadratic convergence: after a step below 1e-12 s the error left is at
    // the rounding level (steps that small are dominated by noise in S).
    const bool done = std::abs(next - s) <= 1e-12 * next;
    s = next;
    if (done) break;
  }
  if (iterations) *iterations = it + 1;
  return s;
}

}  // namespace grains::contact
