#include "contact/correlation/nufft3d.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace grains::correlation {

int fine_grid_size(int n_modes, double sigma, int width) {
  const int n = static_cast<int>(std::ceil(sigma * n_modes));
  return next_fft_size(std::max(n, 2 * width));
}

namespace {

KernelSpec pick_kernel(std::array<int, 3> modes, double eps, const NufftOptions& opt) {
  double sigma = opt.upsampling;
  if (sigma == 0.0) {
    // Auto: 1.25 when there are fewer points than modes (the FFT dominates).
    const double nm = static_cast<double>(modes[0]) * modes[1] * modes[2];
    sigma = (static_cast<double>(opt.expected_points) < nm && kernel_feasible(eps, 1.25, opt.error_model))
                ? 1.25
                : 2.0;
  }
  return choose_kernel(eps, sigma, opt.error_model);
}

std::array<int, 3> pick_fine(std::array<int, 3> modes, const KernelSpec& k) {
  std::array<int, 3> f;
  for (int d = 0; d < 3; ++d) {
    if (modes[d] < 1) throw std::invalid_argument("Nufft3d: every mode count must be >= 1");
    f[d] = fine_grid_size(modes[d], k.sigma, k.width);
  }
  return f;
}

}  // namespace

Nufft3d::Nufft3d(std::array<int, 3> modes, double eps, const NufftOptions& opt)
    : modes_(modes),
      kernel_(pick_kernel(modes, eps, opt)),
      fine_(pick_fine(modes, kernel_)),
      spreader_(fine_, kernel_, opt.threads, opt.max_subproblem),
      grid_(2 * static_cast<std::size_t>(fine_[0]) * fine_[1] * fine_[2]),
      fft_(fine_, modes_, fine_[0], grid_.as_complex(), spreader_.threads(), opt.fftw_flags) {
  for (int d = 0; d < 3; ++d) {
    const int half = modes_[d] / 2;
    const int kmax = std::max(half, modes_[d] - 1 - half);
    const std::vector<double> ph = kernel_fourier_series(kernel_, fine_[d], kmax);
    deconv_[d].resize(modes_[d]);
    for (int i = 0; i < modes_[d]; ++i) deconv_[d][i] = 1.0 / ph[std::abs(i - half)];
  }
}

void Nufft3d::set_points(std::span<const double> x, std::span<const double> y,
                         std::span<const double> z) {
  spreader_.set_points(x, y, z);
}

void Nufft3d::execute_fine_fft(int sign) { fft_.forward_pruned(grid_.as_complex(), sign); }

void Nufft3d::type1(std::span<const Complex> c, std::span<Complex> f, int sign) {
  if (c.size() != num_points()) throw std::invalid_argument("Nufft3d::type1: c has wrong size");
  if (f.size() != num_modes()) throw std::invalid_argument("Nufft3d::type1: f has wrong size");
  grid_.zero();
  spreader_.spread(reinterpret_cast<const double*>(c.data()), 2, grid_.data());
  fft_.forward_pruned(grid_.as_complex(), sign);
  const Complex* g = reinterpret_cast<const Complex*>(grid_.data());
  for_each_mode_row([&](std::size_t grid_row, std::size_t mode_row, double d23, const int* g1) {
    const Complex* row = g + grid_row;
    Complex* out = f.data() + mode_row;
    for (int i1 = 0; i1 < modes_[0]; ++i1) out[i1] = row[g1[i1]] * (d23 * deconv_[0][i1]);
  });
}

void Nufft3d::type2(std::span<const Complex> f, std::span<Complex> c, int sign) {
  if (c.size() != num_points()) throw std::invalid_argument("Nufft3d::type2: c has wrong size");
  if (f.size() != num_modes()) throw std::invalid_argument("Nufft3d::type2: f has wrong size");
  if (c.empty()) return;
  grid_.zero();
  Complex* g = reinterpret_cast<Complex*>(grid_.data());
  for_each_mode_row([&](std::size_t grid_row, std::size_t mode_row, double d23, const int* g1) {
    Complex* row = g + grid_row;
    const Complex* in = f.data() + mode_row;
    for (int i1 = 0; i1 < modes_[0]; ++i1) row[g1[i1]] = in[i1] * (d23 * deconv_[0][i1]);
  });
  fft_.backward_pruned(grid_.as_complex(), sign);
  spreader_.interpolate(grid_.data(), reinterpret_cast<double*>(c.data()));
}

}  // namespace grains::correlation
