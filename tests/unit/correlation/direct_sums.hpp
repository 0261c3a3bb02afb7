#pragma once
// Reference direct sums (NDFT) for the NUFFT tests, with separable phase
// factors so that N = 32^3, M = 1000 stays well under a second.
#include <array>
#include <complex>
#include <vector>

namespace grains::correlation::testing {

using Complex = std::complex<double>;

// Phase tables e^{s i k x_j} for k = -floor(N/2) .. ceil(N/2)-1 (index i).
inline std::vector<Complex> phase_table(const std::vector<double>& x, int n, int sign) {
  std::vector<Complex> t(x.size() * n);
  const int h = n / 2;
  for (std::size_t j = 0; j < x.size(); ++j)
    for (int i = 0; i < n; ++i)
      t[j * n + i] = std::polar(1.0, sign * static_cast<double>(i - h) * x[j]);
  return t;
}

inline std::vector<Complex> direct_type1(const std::vector<double>& x, const std::vector<double>& y,
                                         const std::vector<double>& z,
                                         const std::vector<Complex>& c, std::array<int, 3> n,
                                         int sign) {
  const auto px = phase_table(x, n[0], sign), py = phase_table(y, n[1], sign),
             pz = phase_table(z, n[2], sign);
  std::vector<Complex> f(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
  for (std::size_t j = 0; j < x.size(); ++j)
    for (int i3 = 0; i3 < n[2]; ++i3)
      for (int i2 = 0; i2 < n[1]; ++i2) {
        const Complex a = c[j] * pz[j * n[2] + i3] * py[j * n[1] + i2];
        Complex* row = &f[(static_cast<std::size_t>(i3) * n[1] + i2) * n[0]];
        const Complex* p = &px[j * n[0]];
        for (int i1 = 0; i1 < n[0]; ++i1) row[i1] += a * p[i1];
      }
  return f;
}

inline std::vector<Complex> direct_type2(const std::vector<double>& x, const std::vector<double>& y,
                                         const std::vector<double>& z,
                                         const std::vector<Complex>& f, std::array<int, 3> n,
                                         int sign) {
  const auto px = phase_table(x, n[0], sign), py = phase_table(y, n[1], sign),
             pz = phase_table(z, n[2], sign);
  std::vector<Complex> c(x.size());
  for (std::size_t j = 0; j < x.size(); ++j) {
    Complex s = 0.0;
    for (int i3 = 0; i3 < n[2]; ++i3)
      for (int i2 = 0; i2 < n[1]; ++i2) {
        const Complex* row = &f[(static_cast<std::size_t>(i3) * n[1] + i2) * n[0]];
        const Complex* p = &px[j * n[0]];
        Complex r = 0.0;
        for (int i1 = 0; i1 < n[0]; ++i1) r += row[i1] * p[i1];
        s += r * pz[j * n[2] + i3] * py[j * n[1] + i2];
      }
    c[j] = s;
  }
  return c;
}

inline double rel_l2(const std::vector<Complex>& a, const std::vector<Complex>& ref) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num += std::norm(a[i] - ref[i]);
    den += std::norm(ref[i]);
  }
  return std::sqrt(num / den);
}

}  // namespace grains::correlation::testing
