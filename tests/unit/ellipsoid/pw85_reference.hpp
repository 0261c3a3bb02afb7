#pragma once
// Independent high-precision reference for the PW85 contact function, used by
// the tests only. Arithmetic in __float128 (113-bit significand, ~34 digits):
// Q(lambda)^{-1} r by the adjugate formula (no factorisation shared with the
// solver under test) and the maximum of f by golden-section search on f alone
// (no derivative). The double inputs convert exactly, so the result is the
// contact function of exactly the double data given, to ~1e-30 relative.
#include <Eigen/Core>
#include <array>

namespace grains::test {

using f128 = __float128;

struct Pw85Reference {
  f128 mu2;
  f128 lambda;
};

// sqrt in __float128 by Newton from the double estimate (no libquadmath).
inline f128 sqrt128(f128 x) {
  if (!(x > 0)) return 0;
  f128 y = (f128)__builtin_sqrt((double)x);
  for (int i = 0; i < 3; ++i) y = (y + x / y) / 2;
  return y;
}

inline f128 ref_f(f128 l, const std::array<f128, 3>& r, const std::array<double, 6>& q1,
                  const std::array<double, 6>& q2) {
  const f128 lc = 1 - l;
  f128 q[6];
  for (int i = 0; i < 6; ++i) q[i] = lc * (f128)q1[i] + l * (f128)q2[i];
  const f128 a = q[0], b = q[1], c = q[2], d = q[3], e = q[4], f = q[5];
  // adjugate of [[a b c][b d e][c e f]]
  const f128 A00 = d * f - e * e, A01 = c * e - b * f, A02 = b * e - c * d;
  const f128 A11 = a * f - c * c, A12 = b * c - a * e, A22 = a * d - b * b;
  const f128 det = a * A00 + b * A01 + c * A02;
  const f128 rAr = r[0] * (A00 * r[0] + A01 * r[1] + A02 * r[2]) +
                   r[1] * (A01 * r[0] + A11 * r[1] + A12 * r[2]) +
                   r[2] * (A02 * r[0] + A12 * r[1] + A22 * r[2]);
  return l * lc * rAr / det;
}

inline Pw85Reference pw85_reference(const Eigen::Vector3d& rd, const std::array<double, 6>& q1,
                                    const std::array<double, 6>& q2) {
  const std::array<f128, 3> r{(f128)rd[0], (f128)rd[1], (f128)rd[2]};
  const f128 g = (sqrt128(5) - 1) / 2;
  f128 lo = 0, hi = 1;
  f128 x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  f128 f1 = ref_f(x1, r, q1, q2), f2 = ref_f(x2, r, q1, q2);
  for (int it = 0; it < 200; ++it) {
    if (f1 < f2) {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = ref_f(x2, r, q1, q2);
    } else {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = ref_f(x1, r, q1, q2);
    }
    if (hi - lo < (f128)1e-33 * (lo + (f128)1e-300)) break;
  }
  return f1 > f2 ? Pw85Reference{f1, x1} : Pw85Reference{f2, x2};
}

// Relative difference |x - ref| / |ref| evaluated in __float128.
inline double rel_err(double x, f128 ref) {
  const f128 d = (f128)x - ref;
  const f128 a = ref < 0 ? -ref : ref;
  return (double)((d < 0 ? -d : d) / a);
}

}  // namespace grains::test
