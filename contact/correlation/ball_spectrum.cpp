#include "contact/correlation/ball_spectrum.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include "contact/correlation/ball_kernels.hpp"
#include "contact/correlation/fftw_util.hpp"
#include "contact/correlation/nufft3d.hpp"
#include "contact/correlation/pruned_fft.hpp"
#include "contact/correlation/spreader.hpp"

namespace grains::correlation {

HalfSpectrum::HalfSpectrum(std::array<int, 3> max_mode) : k_(max_mode) {
  for (int d = 0; d < 3; ++d)
    if (k_[d] < 0) throw std::invalid_argument("HalfSpectrum: negative maximum mode");
  data_.assign(static_cast<std::size_t>(k_[0] + 1) * (2 * k_[1] + 1) * (2 * k_[2] + 1),
               Complex(0.0, 0.0));
}

namespace {

inline int pmod(int a, int n) { return ((a % n) + n) % n; }

// B_hat(|k|, r) at the modes |m_d| <= K_d of a box. In a cubic box |k|
// depends on m0^2 + m1^2 + m2^2 alone: one sine and cosine per distinct
// value (3 K^2 + 1 of them) instead of one per mode ((2K + 1)^3 / 2), the
// same numbers to rounding. Other boxes evaluate per mode.
class RadialTransform {
 public:
  RadialTransform(const PeriodicBox& box, std::array<int, 3> K, double r) : r_(r) {
    for (int d = 0; d < 3; ++d) kw_[d] = 2.0 * std::numbers::pi / box.period[d];
    cubic_ = box.period[0] == box.period[1] && box.period[1] == box.period[2];
    if (!cubic_) return;
    const std::size_t nmax = static_cast<std::size_t>(K[0]) * K[0] + static_cast<std::size_t>(K[1]) * K[1] +
                             static_cast<std::size_t>(K[2]) * K[2];
    table_.resize(nmax + 1);
    for (std::size_t n = 0; n <= nmax; ++n)
      table_[n] = ball_indicator_transform(kw_[0] * std::sqrt(static_cast<double>(n)), r);
  }
  double operator()(int m0, int m1, int m2) const {
    if (cubic_) return table_[static_cast<std::size_t>(m0 * m0 + m1 * m1 + m2 * m2)];
    const double k2 = kw_[0] * kw_[0] * m0 * m0 + kw_[1] * kw_[1] * m1 * m1 + kw_[2] * kw_[2] * m2 * m2;
    return ball_indicator_transform(std::sqrt(k2), r_);
  }

 private:
  double r_;
  std::array<double, 3> kw_{};
  bool cubic_ = false;
  std::vector<double> table_;
};

}  // namespace

HalfSpectrum ball_spectrum(const BallSet& balls, const PeriodicBox& box,
                           std::array<int, 3> max_mode, const SpectrumOptions& opt,
                           int* classes) {
  balls.validate("ball_spectrum");
  for (int d = 0; d < 3; ++d)
    if (!(box.period[d] > 0.0)) throw std::invalid_argument("ball_spectrum: period must be > 0");
  HalfSpectrum out(max_mode);
  const int threads = opt.threads > 0 ? opt.threads : omp_get_max_threads();
  // Ball centres may sit on lattices (crystals, the nodes of a query grid):
  // the tolerance must hold at every offset from the fine grid.
  const KernelSpec kernel =
      choose_kernel(std::clamp(opt.tolerance, 1e-14, 1e-1), opt.upsampling, ErrorModel::worst_offset);
  std::array<int, 3> fine;
  for (int d = 0; d < 3; ++d) fine[d] = fine_grid_size(2 * max_mode[d] + 1, kernel.sigma, kernel.width);

  // Radius classes: indices sorted by radius, grouped while within tolerance.
  const std::size_t n = balls.size();
  std::vector<std::size_t> idx(n);
  std::iota(idx.begin(), idx.end(), std::size_t{0});
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return balls.radii[a] < balls.radii[b];
  });
  std::vector<std::size_t> cls_begin;
  for (std::size_t s = 0; s < n; ++s)
    if (s == 0 || balls.radii[idx[s]] > balls.radii[idx[cls_begin.back()]] * (1.0 + opt.radius_class_tol))
      cls_begin.push_back(s);
  cls_begin.push_back(n);
  const int ncls = static_cast<int>(cls_begin.size()) - 1;
  if (classes) *classes = ncls;
  if (ncls == 0) return out;

  Spreader spreader(fine, kernel, threads, 10000);
  // One array for the real grid and its half spectrum: an in-place real FFT,
  // the real rows padded to 2 h0 values (half the memory of two arrays).
  const int h0 = fine[0] / 2 + 1;
  FftwBuffer spec(2 * static_cast<std::size_t>(h0) * fine[1] * fine[2]);
  PrunedRealFft3d fft(fine, max_mode, spec.data(), threads, FFTW_ESTIMATE);

  // 1 / psi_hat per axis for |m| <= K.
  std::array<std::vector<double>, 3> deconv;
  for (int d = 0; d < 3; ++d) {
    deconv[d] = kernel_fourier_series(kernel, fine[d], max_mode[d]);
    for (double& v : deconv[d]) v = 1.0 / v;
  }

  const std::array<int, 3> K = max_mode;
  const std::complex<double>* s = reinterpret_cast<const std::complex<double>*>(spec.data());
  std::vector<double> x, y, z, w;
  for (int c = 0; c < ncls; ++c) {
    const std::size_t b = cls_begin[c], e = cls_begin[c + 1];
    const double r = balls.radii[idx[b]];
    x.clear(); y.clear(); z.clear(); w.clear();
    for (std::size_t q = b; q < e; ++q) {
      const std::size_t i = idx[q];
      x.push_back(2.0 * std::numbers::pi * (balls.centres[3 * i] - box.origin[0]) / box.period[0]);
      y.push_back(2.0 * std::numbers::pi * (balls.centres[3 * i + 1] - box.origin[1]) / box.period[1]);
      z.push_back(2.0 * std::numbers::pi * (balls.centres[3 * i + 2] - box.origin[2]) / box.period[2]);
      w.push_back(balls.weight(i));
    }
    spreader.set_points(x, y, z);
    spec.zero();
    spreader.spread(w.data(), 1, spec.data(), 2 * static_cast<std::size_t>(h0));
    fft.forward(spec.data());
    const RadialTransform bt(box, K, r);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int m2 = -K[2]; m2 <= K[2]; ++m2) {
      const int g2 = pmod(m2, fine[2]);
      for (int m1 = -K[1]; m1 <= K[1]; ++m1) {
        const int g1 = pmod(m1, fine[1]);
        const double d12 = deconv[2][std::abs(m2)] * deconv[1][std::abs(m1)];
        const std::complex<double>* row = s + (static_cast<std::size_t>(g2) * fine[1] + g1) * h0;
        std::complex<double>* o = &out(0, m1, m2);
        for (int m0 = 0; m0 <= K[0]; ++m0) o[m0] += row[m0] * (d12 * deconv[0][m0] * bt(m0, m1, m2));
      }
    }
  }
  return out;
}

HalfSpectrum ball_spectrum_direct(const BallSet& balls, const PeriodicBox& box, std::array<int, 3> K,
                                  int threads) {
  balls.validate("ball_spectrum_direct");
  for (int d = 0; d < 3; ++d)
    if (!(box.period[d] > 0.0)) throw std::invalid_argument("ball_spectrum_direct: period must be > 0");
  HalfSpectrum out(K);
  threads = threads > 0 ? threads : omp_get_max_threads();
  const std::size_t n = balls.size();
  // Per ball and axis: w e^{-i k_d (x_d - o_d)} for m_d in [-K_d, K_d] (the weight on axis 0).
  std::array<std::vector<std::complex<double>>, 3> ph;
  for (int d = 0; d < 3; ++d) {
    const std::size_t w = 2 * static_cast<std::size_t>(K[d]) + 1;
    ph[d].resize(n * w);
    for (std::size_t i = 0; i < n; ++i) {
      const double a = 2.0 * std::numbers::pi * (balls.centres[3 * i + d] - box.origin[d]) / box.period[d];
      for (int m = -K[d]; m <= K[d]; ++m)
        ph[d][i * w + static_cast<std::size_t>(m + K[d])] = (d == 0 ? balls.weight(i) : 1.0) * std::polar(1.0, -a * m);
    }
  }
  // One transform per distinct radius (a grain's balls often share theirs).
  std::vector<RadialTransform> bt;
  std::vector<std::size_t> bt_of(n);
  std::vector<double> bt_r;
  for (std::size_t i = 0; i < n; ++i) {
    const auto it = std::find(bt_r.begin(), bt_r.end(), balls.radii[i]);
    bt_of[i] = static_cast<std::size_t>(it - bt_r.begin());
    if (it == bt_r.end()) {
      bt_r.push_back(balls.radii[i]);
      bt.emplace_back(box, K, balls.radii[i]);
    }
  }
  const std::size_t w0 = 2 * static_cast<std::size_t>(K[0]) + 1, w1 = 2 * static_cast<std::size_t>(K[1]) + 1,
                    w2 = 2 * static_cast<std::size_t>(K[2]) + 1;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int m2 = -K[2]; m2 <= K[2]; ++m2)
    for (int m1 = -K[1]; m1 <= K[1]; ++m1) {
      std::complex<double>* o = &out(0, m1, m2);
      for (std::size_t i = 0; i < n; ++i) {
        const std::complex<double> p12 =
            ph[1][i * w1 + static_cast<std::size_t>(m1 + K[1])] * ph[2][i * w2 + static_cast<std::size_t>(m2 + K[2])];
        const std::complex<double>* p0 = &ph[0][i * w0 + static_cast<std::size_t>(K[0])];
        const RadialTransform& b = bt[bt_of[i]];
        for (int m0 = 0; m0 <= K[0]; ++m0) o[m0] += p0[m0] * p12 * b(m0, m1, m2);
      }
    }
  return out;
}

std::vector<double> synthesize_on_grid(const HalfSpectrum& h, std::array<int, 3> T, int threads,
                                       std::array<int, 3> keep) {
  for (int d = 0; d < 3; ++d) {
    if (T[d] < 1) throw std::invalid_argument("synthesize_on_grid: need >= 1 node per axis");
    if (keep[d] == 0) keep[d] = T[d];
    if (keep[d] < 1 || keep[d] > T[d])
      throw std::invalid_argument("synthesize_on_grid: nodes kept must be 1 .. the grid's per axis");
  }
  threads = threads > 0 ? threads : omp_get_max_threads();
  const std::array<int, 3> K = h.max_mode();
  const int t0 = T[0] / 2 + 1;
  FftwBuffer g(2 * static_cast<std::size_t>(t0) * T[1] * T[2]);
  // In place (g's rows become the padded real rows of the result); only the
  // folded modes' lines are transformed along y and z. Planned before g is
  // filled.
  const std::array<int, 3> kf{std::min(K[0], t0 - 1), K[1], K[2]};
  PrunedRealFft3d fft(T, kf, g.data(), threads, FFTW_ESTIMATE);

  std::complex<double>* G = reinterpret_cast<std::complex<double>*>(g.data());
  // Fold every mode of the box |m_d| <= K_d onto the grid's half spectrum.
  // Parallel over target planes (m2 mod T2) so that no two threads add to the
  // same entry.
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int r2 = 0; r2 < T[2]; ++r2) {
    for (int m2 = -K[2]; m2 <= K[2]; ++m2) {
      if (pmod(m2, T[2]) != r2) continue;
      for (int m1 = -K[1]; m1 <= K[1]; ++m1) {
        std::complex<double>* row = G + (static_cast<std::size_t>(r2) * T[1] + pmod(m1, T[1])) * t0;
        for (int m0 = -K[0]; m0 <= K[0]; ++m0) {
          const int r0 = pmod(m0, T[0]);
          if (r0 >= t0) continue;
          row[r0] += h.at(m0, m1, m2);
        }
      }
    }
  }
  fft.backward(g.data());
  // The kept nodes out of g's padded rows.
  std::vector<double> out(static_cast<std::size_t>(keep[0]) * keep[1] * keep[2]);
  const std::int64_t rows = static_cast<std::int64_t>(keep[1]) * keep[2];
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t r = 0; r < rows; ++r) {
    const std::size_t src = static_cast<std::size_t>(r / keep[1]) * T[1] + static_cast<std::size_t>(r % keep[1]);
    std::copy_n(g.data() + 2 * static_cast<std::size_t>(t0) * src, keep[0],
                out.data() + static_cast<std::size_t>(keep[0]) * static_cast<std::size_t>(r));
  }
  return out;
}

}  // namespace grains::correlation
