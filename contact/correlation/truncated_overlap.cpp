#include "contact/correlation/truncated_overlap.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include "contact/correlation/ball_spectrum.hpp"

namespace grains::correlation {

TruncatedOverlap::TruncatedOverlap(const BallSet& a, const BallSet& b, std::array<double, 3> period,
                                   const TruncatedOverlapOptions& opt)
    : k_(opt.max_mode), period_(period) {
  PeriodicBox box;
  box.period = period;
  SpectrumOptions so;
  so.tolerance = std::clamp(opt.tolerance, 1e-14, 1e-2);
  so.threads = opt.threads;
  const HalfSpectrum sa = ball_spectrum(a, box, k_, so);
  const HalfSpectrum sb = ball_spectrum(b, box, k_, so);
  const double inv_vol = 1.0 / box.volume();

  // Half space: m0 > 0, or m0 = 0 and m1 > 0, or m0 = m1 = 0 and m2 >= 0.
  struct Entry {
    std::array<int, 3> m;
    std::complex<double> c;
    double key;
  };
  std::vector<Entry> e;
  for (int m2 = -k_[2]; m2 <= k_[2]; ++m2)
    for (int m1 = -k_[1]; m1 <= k_[1]; ++m1)
      for (int m0 = 0; m0 <= k_[0]; ++m0) {
        if (m0 == 0 && (m1 < 0 || (m1 == 0 && m2 < 0))) continue;
        const bool origin = (m0 == 0 && m1 == 0 && m2 == 0);
        const std::complex<double> c =
            sa.at(m0, m1, m2) * std::conj(sb.at(m0, m1, m2)) * (origin ? inv_vol : 2.0 * inv_vol);
        double key;
        if (opt.order == ModeOrder::by_frequency) {
          const double k0 = m0 / period[0], k1 = m1 / period[1], k2 = m2 / period[2];
          key = k0 * k0 + k1 * k1 + k2 * k2;
        } else {
          key = -std::abs(c);
        }
        e.push_back({{m0, m1, m2}, c, key});
      }
  std::stable_sort(e.begin(), e.end(), [](const Entry& x, const Entry& y) { return x.key < y.key; });
  coeff_.reserve(e.size());
  mode_.reserve(e.size());
  for (const auto& x : e) {
    coeff_.push_back(x.c);
    mode_.push_back(x.m);
  }
}

double TruncatedOverlap::overlap(const std::array<double, 3>& t, std::size_t m_prime) const {
  m_prime = std::min(m_prime, coeff_.size());
  // Phase tables exp(i k_d m t_d) for m = -K .. K, by one polar() per axis
  // and repeated multiplication (error ~ K ulp, far below the truncation).
  std::array<std::vector<std::complex<double>>, 3> ph;
  for (int d = 0; d < 3; ++d) {
    const int K = k_[d];
    ph[d].resize(2 * K + 1);
    const std::complex<double> step = std::polar(1.0, 2.0 * std::numbers::pi * t[d] / period_[d]);
    ph[d][K] = 1.0;
    std::complex<double> p = 1.0;
    for (int m = 1; m <= K; ++m) {
      p = (m % 16 == 0) ? std::polar(1.0, 2.0 * std::numbers::pi * m * t[d] / period_[d]) : p * step;
      ph[d][K + m] = p;
      ph[d][K - m] = std::conj(p);
    }
  }
  double s = 0.0;
  for (std::size_t q = 0; q < m_prime; ++q) {
    const auto& m = mode_[q];
    const std::complex<double> e = ph[0][k_[0] + m[0]] * ph[1][k_[1] + m[1]] * ph[2][k_[2] + m[2]];
    s += coeff_[q].real() * e.real() - coeff_[q].imag() * e.imag();
  }
  return s;
}

std::array<double, 3> TruncatedOverlap::safe_period(const BallSet& a, const BallSet& b,
                                                    std::array<double, 3> t_max) {
  std::array<double, 3> p{};
  for (int d = 0; d < 3; ++d) {
    double alo = 1e300, ahi = -1e300, blo = 1e300, bhi = -1e300;
    for (std::size_t i = 0; i < a.size(); ++i) {
      alo = std::min(alo, a.centres[3 * i + d] - a.radii[i]);
      ahi = std::max(ahi, a.centres[3 * i + d] + a.radii[i]);
    }
    for (std::size_t j = 0; j < b.size(); ++j) {
      blo = std::min(blo, b.centres[3 * j + d] - b.radii[j]);
      bhi = std::max(bhi, b.centres[3 * j + d] + b.radii[j]);
    }
    // Images of B + t sit at t + q P; none with q != 0 may reach A for
    // |t| <= t_max: P >= max(ahi - blo, bhi - alo) + t_max.
    p[d] = std::max(ahi - blo, bhi - alo) + std::abs(t_max[d]);
  }
  return p;
}

}  // namespace grains::correlation
