#pragma once
// Spreading (non-uniform points -> fine grid) and interpolation (fine grid ->
// points) with the spreading kernel: the two non-FFT halves of the NUFFT.
//
// Points are given in radians on the 2pi-periodic torus (any real value is
// folded), converted to fine-grid coordinates u in [0, n) and sorted into bins
// of 16 x 4 x 4 fine cells, ordered in tiles of 4 x 4 x 4 bins, so that
// consecutive points touch neighbouring memory. Spreading splits each tile's
// points into subproblems of at most `max_subproblem` points; each is spread
// into its own small subgrid (bounding box + kernel width, no wrap-around
// inside) and then added into the periodic fine grid. Threads take whole
// z-slabs of tiles (at least a kernel width thick): first the even slabs,
// then the odd ones, so no two threads ever write the same cell and no
// atomic add is needed; the summation order, and so the result, does not
// depend on the thread count. Interpolation only reads
// the grid and is parallel over points.
//
// Values are real (NC = 1) or complex interleaved (NC = 2).
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "contact/correlation/huge_pages.hpp"
#include "contact/correlation/spreading_kernel.hpp"
#include "contact/correlation/spreader_kernels.hpp"

namespace grains::correlation {

// The instruction set of the spreading arithmetic in use: "avx512", "avx2"
// or "baseline" (the widest the build has and the CPU runs, capped by the
// environment variable GRAINS_SIMD=avx2 or =baseline).
const char* spreading_instruction_set();

class Spreader {
 public:
  Spreader(std::array<int, 3> fine, const KernelSpec& kernel, int threads, int max_subproblem);

  // Folds and sorts the M points (radians, 2pi-periodic). The arrays may be
  // discarded after the call. Throws std::invalid_argument (naming the first
  // such point) if a coordinate is NaN or infinite; the previous points stay.
  void set_points(std::span<const double> x, std::span<const double> y,
                  std::span<const double> z);

  // grid (fine, x fastest, nc doubles per cell) += spread of c (nc doubles per
  // point, in the caller's point order). The grid is not cleared. Its x-rows
  // are `pitch` cells apart (0: n0; e.g. the padded rows of an in-place
  // real-to-complex FFT).
  void spread(const double* c, int nc, double* grid, std::size_t pitch = 0) const;

  // c[j] = sum over the kernel footprint of point j of psi * grid (complex).
  void interpolate(const double* grid, double* c) const;

  std::size_t num_points() const { return points_.size(); }
  const std::array<int, 3>& fine() const { return fine_; }
  const KernelPolynomial& kernel() const { return poly_; }
  int threads() const { return threads_; }

 private:
  std::array<int, 3> fine_;
  KernelPolynomial poly_;
  int threads_;
  int max_sub_;
  std::vector<std::size_t> sub_begin_;       // subproblem boundaries (size + 1)
  std::vector<std::size_t> slab_sub_;        // first subproblem of each z-slab (size + 1)
  // set_points scratch (kept: no page faults on reuse)
  std::vector<std::uint32_t, LargeAllocator<std::uint32_t>> bin_;
  // sorted fine-grid coordinates + caller index
  std::vector<detail::SortedPoint, LargeAllocator<detail::SortedPoint>> points_;
};

}  // namespace grains::correlation
