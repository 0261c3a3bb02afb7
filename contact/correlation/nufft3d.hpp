#pragma once
// 3D non-uniform FFT of type 1 and type 2 on FFTW3.
//
//   type 1 (adjoint NFFT, points -> modes):  f_k = sum_j c_j exp(s i k.x_j)
//   type 2 (NFFT, modes -> points):          c_j = sum_k f_k exp(s i k.x_j)
//
// with s = +1 or -1, points x_j in radians on the 2pi-periodic torus (any real
// value; a point on the period boundary 2pi is the same as 0), and the modes
// k = (k1, k2, k3) with k_d = -floor(N_d/2) .. ceil(N_d/2) - 1, stored x
// fastest: f[(i3 * N2 + i2) * N1 + i1] holds k_d = i_d - floor(N_d/2).
// Type 2 with sign -s is the adjoint of type 1 with sign s.
//
// Method: spread with the PSWF kernel onto a fine grid of n_d >= sigma N_d
// nodes (next 2,3,5-smooth even size), FFT of the fine grid, then divide by
// the kernel's Fourier transform (deconvolution) and truncate to the N modes;
// type 2 runs the same steps backwards. The fine-grid FFT skips the lines
// whose results are not needed (PrunedFft3d); its FFTW plans for both signs
// are made once in the constructor and reused by every call.
#include <array>
#include <complex>
#include <cstddef>
#include <span>
#include <vector>

#include "contact/correlation/spreading_kernel.hpp"
#include "contact/correlation/fftw_util.hpp"
#include "contact/correlation/pruned_fft.hpp"
#include "contact/correlation/spreader.hpp"

namespace grains::correlation {

struct NufftOptions {
  // Fine-grid upsampling factor: 2 (default) or e.g. 1.25, which shrinks the
  // FFT (4.1x fewer fine nodes) at the price of a wider kernel; 0 picks 1.25
  // when the FFT is expected to dominate (few points per mode) and the
  // tolerance allows it, else 2.
  double upsampling = 2.0;
  int threads = 0;                      // 0: omp_get_max_threads()
  unsigned fftw_flags = FFTW_ESTIMATE;  // FFTW_MEASURE pays off for repeated calls
  // Points per spreading subproblem. Results do not depend on `threads`
  // (bitwise); they depend on this to rounding (it fixes the summation order).
  int max_subproblem = 10000;
  std::size_t expected_points = 0;      // only used by upsampling = 0
  // What eps bounds: the relative l2 error for points in general position
  // (default), or for every point at its worst offset from the fine grid
  // (points on a lattice commensurate with it; costs about one node of
  // kernel width). spreading_kernel.hpp.
  ErrorModel error_model = ErrorModel::general_position;
};

class Nufft3d {
 public:
  using Complex = std::complex<double>;

  // modes: N_d >= 1 per dimension; eps in [1e-14, 1e-1].
  Nufft3d(std::array<int, 3> modes, double eps, const NufftOptions& opt = {});

  // Points in radians (2pi-periodic). Sorted once; reused by every transform
  // until the next call. M = 0 is allowed (every transform returns zeros).
  // A NaN or infinite coordinate throws std::invalid_argument naming the
  // point; the previous points stay set.
  void set_points(std::span<const double> x, std::span<const double> y,
                  std::span<const double> z);

  // f (N1 N2 N3 modes) = type 1 of c (M strengths).
  void type1(std::span<const Complex> c, std::span<Complex> f, int sign);
  // c (M values) = type 2 of f (N1 N2 N3 modes).
  void type2(std::span<const Complex> f, std::span<Complex> c, int sign);

  std::array<int, 3> modes() const { return modes_; }
  std::array<int, 3> fine() const { return fine_; }
  std::size_t num_modes() const {
    return static_cast<std::size_t>(modes_[0]) * modes_[1] * modes_[2];
  }
  std::size_t num_points() const { return spreader_.num_points(); }
  const KernelSpec& kernel() const { return kernel_; }

  // The fine-grid FFT of type 1 (pruned) alone, timed by the benchmarks.
  void execute_fine_fft(int sign);

 private:
  // Calls fn(fine-grid row offset, mode row offset, deconvolution weight of
  // the (i2, i3) row, fine-grid index of each i1) for every row of modes,
  // rows in parallel: the shared index map of type 1 (gather from the fine
  // grid) and type 2 (scatter into it); distinct modes map to distinct
  // fine-grid points, so the rows never collide.
  template <class Fn>
  void for_each_mode_row(Fn&& fn) const {
    const int N1 = modes_[0], N2 = modes_[1], N3 = modes_[2];
    const int h1 = N1 / 2, h2 = N2 / 2, h3 = N3 / 2;
    const int n1 = fine_[0], n2 = fine_[1], n3 = fine_[2];
    std::vector<int> g1(static_cast<std::size_t>(N1));
    for (int i1 = 0; i1 < N1; ++i1) g1[i1] = i1 - h1 < 0 ? i1 - h1 + n1 : i1 - h1;
#pragma omp parallel for num_threads(spreader_.threads()) schedule(static)
    for (int i3 = 0; i3 < N3; ++i3) {
      const int g3 = ((i3 - h3) % n3 + n3) % n3;
      for (int i2 = 0; i2 < N2; ++i2) {
        const int g2 = ((i2 - h2) % n2 + n2) % n2;
        fn((static_cast<std::size_t>(g3) * n2 + g2) * n1, (static_cast<std::size_t>(i3) * N2 + i2) * N1,
           deconv_[2][i3] * deconv_[1][i2], g1.data());
      }
    }
  }

  std::array<int, 3> modes_;
  KernelSpec kernel_;
  std::array<int, 3> fine_;
  Spreader spreader_;
  FftwBuffer grid_;
  PrunedFft3d fft_;
  std::array<std::vector<double>, 3> deconv_;  // 1 / psi_hat(k), index i_d
};

// Fine-grid size for N modes with upsampling sigma and kernel width w.
int fine_grid_size(int n_modes, double sigma, int width);

}  // namespace grains::correlation
