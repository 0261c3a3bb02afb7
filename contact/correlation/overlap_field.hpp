#pragma once
// Overlap of a shape with a whole scene over all translations: the
// translational configuration-space obstacle of the seed (Sec. 3.2, 4.1).
//
//   V(t) = sum_i sum_j w_i v_j |B(x_i, r_i) ∩ B(t + R y_j, s_j)|
//        = (1_scene ⋆ 1_{R shape})(t),
//
// for a shape given as balls (y_j, s_j) about its reference point (a sphere:
// one ball at 0; a clump: its member balls) at a fixed orientation R, and the
// scene's balls (x_i, r_i). In Fourier space the correlation is a product,
// V_hat = F_scene conj(F_shape) / |box| (seed eq. 47), computed with the
// NUFFT-based ball spectra and one inverse FFT onto the grid of translations.
//
// Where V(t) = 0 the shape placed at t overlaps nothing: the free insertion
// positions. V is only C^1 (lens volumes grow like the square of the
// penetration), so its truncated Fourier series converges like a power of the
// number of modes, not exponentially: read candidates as V <= threshold and
// confirm them with an exact contact check (or inflate the shape's radii by a
// margin, which makes true free positions strictly zero with room to spare).
// The measured error against the exact lens sums is in docs/nfft.md.
#include <array>
#include <vector>

#include "contact/correlation/ball_set.hpp"
#include "contact/correlation/ball_spectrum.hpp"

namespace grains::correlation {

struct OverlapFieldOptions {
  // Modes kept per axis: |m_d| <= mode_factor * T_d / 2, T_d the nodes of the
  // (padded) periodic box; more modes, smaller truncation error.
  double mode_factor = 2.0;
  double tolerance = 1e-6;  // NUFFT tolerance
  double upsampling = 2.0;
  int threads = 0;
};

struct OverlapFieldInfo {
  std::array<int, 3> max_mode{};
  std::array<int, 3> fft_nodes{};
};

// rotation: row-major 3x3 matrix R applied to the shape's ball centres.
// Returns V at the grid's nodes (translations t), x fastest. Along
// non-periodic axes the scene is padded so that no translation sees a
// periodic image; walls are the caller's business.
std::vector<double> translational_overlap_field(const BallSet& scene, const BallSet& shape,
                                                const std::array<double, 9>& rotation,
                                                const GridSpec& grid,
                                                const OverlapFieldOptions& opt = {},
                                                OverlapFieldInfo* info = nullptr);

// Indices of the nodes where field <= threshold (x-fastest node indices).
std::vector<std::size_t> free_nodes(const std::vector<double>& field, double threshold);

// The scene's spectrum computed once and correlated with many shapes or
// orientations (an insertion tries several orientations of a grain against
// the same scene). Unlike translational_overlap_field, the scene's balls may
// lie anywhere within `reach` + their radius of the grid's nodes (outside the
// grid's box too, e.g. the grains around an insertion region): every
// non-periodic axis is padded by twice that distance, so no translation of
// the grid sees a periodic image. `reach` bounds |R y_j| + s_j of every shape
// passed to field(), which refuses larger shapes.
class SceneOverlap {
 public:
  SceneOverlap(const BallSet& scene, const GridSpec& grid, double reach, const OverlapFieldOptions& opt = {});
  // V at the grid's nodes for `shape` rotated by `rotation` (x fastest).
  std::vector<double> field(const BallSet& shape, const std::array<double, 9>& rotation) const;
  const OverlapFieldInfo& info() const { return info_; }

 private:
  GridSpec grid_;
  OverlapFieldOptions opt_;
  double reach_;
  PeriodicBox box_;
  OverlapFieldInfo info_;
  HalfSpectrum scene_;
};

// The identity rotation, for convenience.
inline constexpr std::array<double, 9> kIdentityRotation = {1, 0, 0, 0, 1, 0, 0, 0, 1};

}  // namespace grains::correlation
