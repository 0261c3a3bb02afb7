#include "contact/correlation/overlap_field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "contact/correlation/ball_spectrum.hpp"
#include "contact/correlation/fftw_util.hpp"

namespace grains::correlation {

std::vector<double> translational_overlap_field(const BallSet& scene, const BallSet& shape,
                                                const std::array<double, 9>& R,
                                                const GridSpec& grid,
                                                const OverlapFieldOptions& opt,
                                                OverlapFieldInfo* info) {
  scene.validate("translational_overlap_field (scene)");
  shape.validate("translational_overlap_field (shape)");
  grid.validate("translational_overlap_field");
  if (!(opt.mode_factor > 0.0))
    throw std::invalid_argument("translational_overlap_field: mode_factor must be > 0");

  // Rotated shape centres, and the shape's reach about its reference point.
  std::vector<double> rc(shape.centres.size());
  double reach = 0.0;
  for (std::size_t j = 0; j < shape.size(); ++j) {
    const double* y = &shape.centres[3 * j];
    for (int a = 0; a < 3; ++a) rc[3 * j + a] = R[3 * a] * y[0] + R[3 * a + 1] * y[1] + R[3 * a + 2] * y[2];
    reach = std::max(reach, std::sqrt(rc[3 * j] * rc[3 * j] + rc[3 * j + 1] * rc[3 * j + 1] +
                                      rc[3 * j + 2] * rc[3 * j + 2]) +
                                shape.radii[j]);
  }
  double rmax = 0.0;
  for (double r : scene.radii) rmax = std::max(rmax, r);

  PeriodicBox box;
  std::array<int, 3> T, K;
  for (int d = 0; d < 3; ++d) {
    const double h = grid.spacing[d];
    T[d] = grid.periodic[d]
               ? grid.dims[d]
               : next_fft_size(grid.dims[d] + static_cast<int>(std::ceil((rmax + reach) / h)) + 1);
    box.origin[d] = grid.origin[d];
    box.period[d] = T[d] * h;
    K[d] = std::max(1, static_cast<int>(std::floor(opt.mode_factor * T[d] / 2.0)));
  }
  SpectrumOptions so;
  so.tolerance = std::clamp(opt.tolerance, 1e-14, 1e-2);
  so.upsampling = opt.upsampling;
  so.threads = opt.threads;
  HalfSpectrum fs = ball_spectrum(scene, box, K, so);
  PeriodicBox shape_box = box;
  shape_box.origin = {0.0, 0.0, 0.0};  // shape about its reference point
  const BallSet rotated{rc, shape.radii, shape.weights};
  const HalfSpectrum gs = ball_spectrum(rotated, shape_box, K, so);

  const double inv_vol = 1.0 / box.volume();
  auto& a = fs.data();
  const auto& b = gs.data();
  for (std::size_t q = 0; q < a.size(); ++q) a[q] *= std::conj(b[q]) * inv_vol;
  if (info) {
    info->max_mode = K;
    info->fft_nodes = T;
  }
  return synthesize_on_grid(fs, T, opt.threads, grid.dims);
}

SceneOverlap::SceneOverlap(const BallSet& scene, const GridSpec& grid, double reach, const OverlapFieldOptions& opt)
    : grid_(grid), opt_(opt), reach_(reach) {
  scene.validate("SceneOverlap (scene)");
  grid.validate("SceneOverlap");
  if (!(opt.mode_factor > 0.0)) throw std::invalid_argument("SceneOverlap: mode_factor must be > 0");
  if (!(reach >= 0.0)) throw std::invalid_argument("SceneOverlap: reach must be >= 0");
  double rmax = 0.0;
  for (double r : scene.radii) rmax = std::max(rmax, r);
  std::array<int, 3> K;
  for (int d = 0; d < 3; ++d) {
    const double h = grid.spacing[d];
    // Balls up to rmax + reach beyond either end of the grid: an image one
    // period away must stay farther than that from every node.
    info_.fft_nodes[d] = grid.periodic[d] ? grid.dims[d]
                                          : next_fft_size(grid.dims[d] +
                                                          static_cast<int>(std::ceil(2.0 * (rmax + reach) / h)) + 1);
    box_.origin[d] = grid.origin[d];
    box_.period[d] = info_.fft_nodes[d] * h;
    K[d] = std::max(1, static_cast<int>(std::floor(opt.mode_factor * info_.fft_nodes[d] / 2.0)));
  }
  info_.max_mode = K;
  SpectrumOptions so;
  so.tolerance = std::clamp(opt.tolerance, 1e-14, 1e-2);
  so.upsampling = opt.upsampling;
  so.threads = opt.threads;
  scene_ = ball_spectrum(scene, box_, K, so);
}

std::vector<double> SceneOverlap::field(const BallSet& shape, const std::array<double, 9>& R) const {
  shape.validate("SceneOverlap::field (shape)");
  std::vector<double> rc(shape.centres.size());
  for (std::size_t j = 0; j < shape.size(); ++j) {
    const double* y = &shape.centres[3 * j];
    for (int a = 0; a < 3; ++a) rc[3 * j + a] = R[3 * a] * y[0] + R[3 * a + 1] * y[1] + R[3 * a + 2] * y[2];
    const double far = std::sqrt(rc[3 * j] * rc[3 * j] + rc[3 * j + 1] * rc[3 * j + 1] + rc[3 * j + 2] * rc[3 * j + 2]) +
                       shape.radii[j];
    if (far > reach_ * (1.0 + 1e-12))
      throw std::invalid_argument("SceneOverlap::field: the shape reaches farther than the reach it was built for");
  }
  PeriodicBox shape_box = box_;
  shape_box.origin = {0.0, 0.0, 0.0};
  SpectrumOptions so;
  so.tolerance = std::clamp(opt_.tolerance, 1e-14, 1e-2);
  so.upsampling = opt_.upsampling;
  so.threads = opt_.threads;
  // A grain's few balls: summed directly (exact, and cheaper than a
  // spreading pass and a fine-grid FFT per radius); many balls: the NUFFT.
  const BallSet rotated{rc, shape.radii, shape.weights};
  HalfSpectrum prod = shape.size() <= 64 ? ball_spectrum_direct(rotated, shape_box, info_.max_mode, opt_.threads)
                                         : ball_spectrum(rotated, shape_box, info_.max_mode, so);
  // The correlation's spectrum in place of the shape's (no copy of the scene's).
  const double inv_vol = 1.0 / box_.volume();
  auto& a = prod.data();
  const auto& b = scene_.data();
  for (std::size_t q = 0; q < a.size(); ++q) a[q] = b[q] * std::conj(a[q]) * inv_vol;
  return synthesize_on_grid(prod, info_.fft_nodes, opt_.threads, grid_.dims);
}

std::vector<std::size_t> free_nodes(const std::vector<double>& field, double threshold) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < field.size(); ++i)
    if (field[i] <= threshold) out.push_back(i);
  return out;
}

}  // namespace grains::correlation
