#pragma once
// Fourier coefficients of a weighted union of balls on a periodic box:
//
//   F(m) = sum_i w_i exp(-i k.(x_i - origin)) B_hat(|k|, r_i),   k_d = 2 pi m_d / P_d,
//
// with B_hat(k, r) = 4 pi (sin kr - kr cos kr) / k^3 the ball indicator's
// transform, for every mode |m_d| <= K_d. This is the seed's equation (22):
// the knot density's transform (a type-1 NUFFT) times the primitive's
// transform, with one spreading pass and one real FFT per radius class.
// The spreading, the FFT and the deconvolution are the NUFFT's; fusing the
// class multipliers into the deconvolution avoids storing one spectrum per
// class. F(-m) = conj F(m) (real weights), so only m0 >= 0 is stored.
#include <array>
#include <complex>
#include <vector>

#include "contact/correlation/ball_set.hpp"

namespace grains::correlation {

struct PeriodicBox {
  std::array<double, 3> origin{0.0, 0.0, 0.0};
  std::array<double, 3> period{1.0, 1.0, 1.0};
  double volume() const { return period[0] * period[1] * period[2]; }
};

struct SpectrumOptions {
  double tolerance = 1e-6;          // NUFFT tolerance (relative)
  double upsampling = 2.0;          // fine grid factor (2 or 1.25)
  int threads = 0;                  // 0: omp_get_max_threads()
  double radius_class_tol = 1e-12;  // radii within this relative gap share a class
};

// Half-spectrum array over m0 in [0, K0], m1 in [-K1, K1], m2 in [-K2, K2].
class HalfSpectrum {
 public:
  using Complex = std::complex<double>;
  HalfSpectrum() = default;
  explicit HalfSpectrum(std::array<int, 3> max_mode);

  const std::array<int, 3>& max_mode() const { return k_; }
  std::size_t index(int m0, int m1, int m2) const {
    return (static_cast<std::size_t>(m2 + k_[2]) * (2 * k_[1] + 1) + (m1 + k_[1])) * (k_[0] + 1) +
           m0;
  }
  // Any |m_d| <= K_d; m0 < 0 via Hermitian symmetry.
  Complex at(int m0, int m1, int m2) const {
    return m0 >= 0 ? data_[index(m0, m1, m2)] : std::conj(data_[index(-m0, -m1, -m2)]);
  }
  Complex& operator()(int m0, int m1, int m2) { return data_[index(m0, m1, m2)]; }
  std::vector<Complex>& data() { return data_; }
  const std::vector<Complex>& data() const { return data_; }

 private:
  std::array<int, 3> k_{0, 0, 0};
  std::vector<Complex> data_;
};

// Computes the coefficients above. Returns the number of radius classes via
// classes (optional).
HalfSpectrum ball_spectrum(const BallSet& balls, const PeriodicBox& box,
                           std::array<int, 3> max_mode, const SpectrumOptions& opt = {},
                           int* classes = nullptr);

// The same coefficients by direct summation over the balls, O(balls x
// modes): exact (no NUFFT tolerance) and faster than the spreading and the
// fine-grid FFT for a handful of balls (a grain's shape).
HalfSpectrum ball_spectrum_direct(const BallSet& balls, const PeriodicBox& box, std::array<int, 3> max_mode,
                                  int threads = 0);

// Real field f(i) = sum_m H(m) exp(2 pi i sum_d m_d i_d / T_d) at the nodes
// i_d = 0 .. T_d - 1 of a periodic grid, for a Hermitian H given on its half
// spectrum. Modes beyond the grid's Nyquist fold onto their aliases, which
// is exact at the nodes. One complex-to-real FFT of the T grid. Values x
// fastest; only the first `keep`_d nodes per axis are returned (0 or absent:
// all T_d; at most T_d).
std::vector<double> synthesize_on_grid(const HalfSpectrum& h, std::array<int, 3> nodes, int threads = 0,
                                       std::array<int, 3> keep = {0, 0, 0});

}  // namespace grains::correlation
