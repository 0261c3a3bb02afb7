#include "contact/correlation/solid_fraction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "contact/correlation/ball_spectrum.hpp"
#include "contact/correlation/fftw_util.hpp"

namespace grains::correlation {

std::vector<double> solid_fraction_field(const BallSet& balls, const GridSpec& grid,
                                         const SolidFractionOptions& opt,
                                         SolidFractionInfo* info) {
  balls.validate("solid_fraction_field");
  grid.validate("solid_fraction_field");
  if (!(opt.tolerance > 0.0 && opt.tolerance < 1.0))
    throw std::invalid_argument("solid_fraction_field: tolerance must be in (0, 1)");
  const double l = opt.smoothing_length >= 0.0
                       ? opt.smoothing_length
                       : *std::max_element(grid.spacing.begin(), grid.spacing.end());
  double rmax = 0.0;
  for (double r : balls.radii) rmax = std::max(rmax, r);
  // Gaussian reach (where it falls below the tolerance) in space and frequency.
  const double reach = std::sqrt(2.0 * std::log(1.0 / opt.tolerance));

  PeriodicBox box;
  std::array<int, 3> T, K;
  long total = 1;
  for (int d = 0; d < 3; ++d) {
    const double h = grid.spacing[d];
    T[d] = grid.periodic[d]
               ? grid.dims[d]
               : next_fft_size(grid.dims[d] + static_cast<int>(std::ceil((rmax + reach * l) / h)) + 1);
    box.origin[d] = grid.origin[d];
    box.period[d] = T[d] * h;
    if (l > 0.0) {
      const double kcut = reach / l;
      K[d] = static_cast<int>(std::ceil(kcut * box.period[d] / (2.0 * std::numbers::pi)));
    } else {
      K[d] = (T[d] - 1) / 2;
    }
    total *= 2L * K[d] + 1;
  }
  if (total > opt.max_modes)
    throw std::invalid_argument(
        "solid_fraction_field: smoothing length " + std::to_string(l) +
        " needs too many Fourier modes on this box; use a larger smoothing length or tolerance");

  SpectrumOptions so;
  so.tolerance = std::clamp(opt.tolerance, 1e-14, 1e-2);
  so.upsampling = opt.upsampling;
  so.threads = opt.threads;
  int classes = 0;
  HalfSpectrum h = ball_spectrum(balls, box, K, so, &classes);

  // Times the Gaussian's transform exp(-l^2 |k|^2 / 2), a product of one
  // factor per axis, and 1 / box volume.
  std::array<std::vector<double>, 3> gauss;
  for (int d = 0; d < 3; ++d) {
    gauss[d].resize(static_cast<std::size_t>(K[d]) + 1);
    for (int m = 0; m <= K[d]; ++m) {
      const double k = 2.0 * std::numbers::pi * m / box.period[d];
      gauss[d][m] = std::exp(-0.5 * k * k * l * l);
    }
  }
  const double inv_vol = 1.0 / box.volume();
  for (int m2 = -K[2]; m2 <= K[2]; ++m2)
    for (int m1 = -K[1]; m1 <= K[1]; ++m1) {
      const double g12 = inv_vol * gauss[2][std::abs(m2)] * gauss[1][std::abs(m1)];
      for (int m0 = 0; m0 <= K[0]; ++m0) h(m0, m1, m2) *= g12 * gauss[0][m0];
    }

  if (info) {
    info->max_mode = K;
    info->fft_nodes = T;
    info->radius_classes = classes;
  }
  return synthesize_on_grid(h, T, opt.threads, grid.dims);
}

}  // namespace grains::correlation
