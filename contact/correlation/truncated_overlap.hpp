#pragma once
// Truncated-mode ("time-critical") overlap query for one configuration
// (seed Sec. 4.1, eq. 50, and Fig. 9): by Parseval, the overlap volume of two
// ball sets A and B + t is
//
//   V(t) = (1/|P|) sum_m A_hat(m) conj(B_hat(m)) exp(i k.t),
//
// on a periodic box P large enough that no periodic image of B + t reaches A.
// Keeping only the m' dominant modes trades accuracy for time: the query
// costs O(m') after an O(K) phase table, independent of the ball counts.
//
// The spectra are computed once (NUFFT, ball_spectrum); the mode products
// are sorted once, lowest |k| first (the "spiral traversal" of the seed) or
// largest |A_hat B_hat| first. Real fields: only half the spectrum is stored,
// each entry standing for the pair +-m.
#include <array>
#include <complex>
#include <cstddef>
#include <vector>

#include "contact/correlation/ball_set.hpp"

namespace grains::correlation {

enum class ModeOrder { by_frequency, by_magnitude };

struct TruncatedOverlapOptions {
  std::array<int, 3> max_mode{24, 24, 24};  // spectra computed for |m_d| <= max_mode_d
  double tolerance = 1e-9;                  // NUFFT tolerance of the spectra
  ModeOrder order = ModeOrder::by_frequency;
  int threads = 0;
};

class TruncatedOverlap {
 public:
  // a and b in their own frames (b about its reference point); b is at a
  // fixed orientation (rotate its centres before calling for another one).
  // period: side lengths of the periodic box; it must exceed, per axis, the
  // extent of A plus the extent of B plus the largest |t| queried.
  TruncatedOverlap(const BallSet& a, const BallSet& b, std::array<double, 3> period,
                   const TruncatedOverlapOptions& opt = {});

  // Overlap volume of A and B + t from the first m_prime half-spectrum
  // entries (each standing for the pair +-m, so 2 m_prime - 1 modes of the
  // full spectrum); m_prime is clamped to num_modes().
  double overlap(const std::array<double, 3>& t, std::size_t m_prime) const;

  std::size_t num_modes() const { return coeff_.size(); }

  // A period that satisfies the condition above for |t_d| <= t_max_d.
  static std::array<double, 3> safe_period(const BallSet& a, const BallSet& b,
                                           std::array<double, 3> t_max);

 private:
  std::array<int, 3> k_;
  std::array<double, 3> period_;
  std::vector<std::complex<double>> coeff_;  // A conj(B) / |P|, times 2 off the origin
  std::vector<std::array<int, 3>> mode_;     // m, sorted
};

}  // namespace grains::correlation
