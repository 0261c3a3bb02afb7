#pragma once
// Solid-fraction field of a packing of balls on a user grid.
//
// The field is the coarse-grained solid fraction
//
//   phi(x) = sum_i w_i (1_{B(x_i, r_i)} * G_l)(x),
//
// G_l the normalised isotropic Gaussian of standard deviation l per axis (the
// usual coarse-graining of granular physics; l = 0 gives the raw truncated
// Fourier series of the indicator sum, Gibbs ripples included). Its mean over
// the periodic box is exactly the solid volume over the box volume, and its
// integral over any region well inside (several l from the balls crossing its
// surface) is the solid volume there.
//
// Method (seed Sec. 2.5): per radius class one spreading pass and one FFT
// (a type-1 NUFFT) give the knot density's transform; times the ball's
// transform 4 pi (sin kr - kr cos kr)/k^3 and the Gaussian's exp(-k^2 l^2/2);
// the modes are folded onto the grid and one inverse FFT gives the nodes.
// The modes kept are those where the Gaussian exceeds the tolerance, so the
// error at the nodes is about `tolerance` (NUFFT + Gaussian tail), whatever
// the grid spacing.
//
// Overlapping balls count their shared volume once per ball (see BallSet).
// Non-periodic axes are padded by the largest radius plus the Gaussian's
// reach, so nothing wraps around; the field there is that of the balls alone.
#include <vector>

#include "contact/correlation/ball_set.hpp"

namespace grains::correlation {

struct SolidFractionOptions {
  double smoothing_length = -1.0;  // l in metres; < 0: the largest grid spacing
  double tolerance = 1e-6;         // absolute, on the field values
  double upsampling = 2.0;         // NUFFT fine grid factor (2 or 1.25)
  int threads = 0;                 // 0: omp_get_max_threads()
  long max_modes = 1L << 27;       // guard against a tiny l on a large box
};

struct SolidFractionInfo {
  std::array<int, 3> max_mode{};   // modes kept per axis: |m_d| <= max_mode_d
  std::array<int, 3> fft_nodes{};  // node grid of the (padded) periodic box
  int radius_classes = 0;
};

// Values at the grid's nodes, x fastest (grid.num_nodes() entries).
std::vector<double> solid_fraction_field(const BallSet& balls, const GridSpec& grid,
                                         const SolidFractionOptions& opt = {},
                                         SolidFractionInfo* info = nullptr);

}  // namespace grains::correlation
