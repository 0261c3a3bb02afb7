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

  // Times the Gaussian's transform and 1 / box volume.
  const double inv_vol = 1.0 / box.volume();
  for (int m2 = -K[2]; m2 <= K[2]; ++m2)
    for (int m1 = -K[1]; m1 <= K[1]; ++m1)
      for (int m0 = 0; m0 <= K[0]; ++m0) {
        const double k0 = 2.0 * std::numbers::pi * m0 / box.period[0];
        const double k1 = 2.0 * std::numbers::pi * m1 / box.period[1];
        const double k2 = 2.0 * std::numbers::pi * m2 / box.period[2];
        const double k2sum = k0 * k0 + k1 * k1 + k2 * k2;
        h(m0, m1, m2) *= inv_vol * std::exp(-0.5 * k2sum * l * l);
      }
  std::vector<double> full = synthesize_on_grid(h, T, opt.threads);

  if (info) {
    info->max_mode = K;
    info->fft_nodes = T;
    info->radius_classes = classes;
  }
  return crop_nodes(full, T, grid.dims);
}

}  // namespace grains::correlation
