#include "contact/correlation/spreader.hpp"

#include <omp.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact/correlation/spreader_kernels.hpp"

#define GRAINS_SPREAD_SUFFIX baseline
#include "contact/correlation/spreader_kernels.inc"
#undef GRAINS_SPREAD_SUFFIX

namespace grains::correlation {

namespace {

// The copy of the spreading arithmetic in use: the widest instruction set
// this build has and the CPU runs. GRAINS_SIMD=baseline or =avx2 caps it
// (for comparisons, and so that the tests exercise every copy on one machine).
struct ArithmeticCopy {
  const char* name;
  void (*spread)(int, int, const detail::SpreadTask&);
  void (*interpolate)(int, const detail::InterpolateTask&);
  int (*row_cells)(int, int, int);
};

const ArithmeticCopy& arithmetic() {
  static const ArithmeticCopy copy = []() -> ArithmeticCopy {
    const ArithmeticCopy baseline{"baseline", detail::spread_baseline, detail::interpolate_baseline,
                                  detail::spread_row_cells_baseline};
#if GRAINS_SPREAD_AVX2
    const char* env = std::getenv("GRAINS_SIMD");
    const std::string cap = env ? env : "";
    if (cap == "baseline") return baseline;
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) return baseline;
    if (cap != "avx2" && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
        __builtin_cpu_supports("avx512dq"))
      return {"avx512", detail::spread_avx512, detail::interpolate_avx512, detail::spread_row_cells_avx512};
    return {"avx2", detail::spread_avx2, detail::interpolate_avx2, detail::spread_row_cells_avx2};
#else
    return baseline;
#endif
  }();
  return copy;
}

constexpr std::array<int, 3> kBin = {16, 4, 4};
// Bins are ordered tile by tile (4 x 4 x 4 bins = 64 x 16 x 16 cells), and a
// spreading subproblem never leaves its tile: its subgrid stays small and
// compact however sparse the points are (with plain row order, 10^4 sparse
// points spanned whole x-rows of the grid, and clearing and adding back
// their subgrids cost more than the spreading).
constexpr int kTile = 4;

// ceil(u - w/2) without a libm call (u is a fine-grid coordinate in [0, n)).
inline int first_node(double u, int w) {
  const double v = 0.5 * w - u;
  const int i = static_cast<int>(v);
  return -(i - (static_cast<double>(i) > v));
}

// t - floor(t) times n, folded into [0, n): the fine-grid coordinate of a
// point at t periods. floor is taken as a truncation of t + 2^31 (positive,
// so truncation is floor; no libm call and no data-dependent branch: with
// `fl -= (fl > t)` the compiler branched on the sign of t, mispredicted half
// the time for points in [-pi, pi)). Rounding t + 2^31 can only move fl up
// by one for t just below an integer; the result is then a hair below 0 and
// the rarely taken fix-ups below bring it into [0, n).
inline double fold(double t, int n) {
  constexpr double kShift = 2147483648.0;  // 2^31
  double fl;
  if (std::abs(t) < kShift) {
    fl = static_cast<double>(static_cast<std::int64_t>(t + kShift) - static_cast<std::int64_t>(kShift));
  } else {
    fl = std::floor(t);  // also keeps NaN away from the integer conversion
  }
  double v = (t - fl) * n;
  if (v >= n) v -= n;
  if (v < 0.0) v += n;
  if (!(v < n)) v = 0.0;  // rounding to n, or a non-finite input
  return v;
}

}  // namespace

const char* spreading_instruction_set() { return arithmetic().name; }

Spreader::Spreader(std::array<int, 3> fine, const KernelSpec& kernel, int threads, int max_subproblem)
    : fine_(fine),
      poly_(fit_kernel_polynomial(kernel)),
      threads_(threads > 0 ? threads : omp_get_max_threads()),
      max_sub_(std::max(1, max_subproblem)) {
  for (int d = 0; d < 3; ++d)
    if (fine_[d] < 2 * kernel.width)
      throw std::invalid_argument("Spreader: fine grid smaller than twice the kernel width");
}

void Spreader::set_points(std::span<const double> x, std::span<const double> y, std::span<const double> z) {
  const std::size_t m = x.size();
  if (y.size() != m || z.size() != m) throw std::invalid_argument("Spreader::set_points: x, y, z differ in length");
  std::array<int, 3> nb, nt;
  for (int d = 0; d < 3; ++d) {
    nb[d] = (fine_[d] + kBin[d] - 1) / kBin[d];
    nt[d] = (nb[d] + kTile - 1) / kTile;
  }
  constexpr std::uint32_t tile_bins = kTile * kTile * kTile;
  const std::size_t ntiles = static_cast<std::size_t>(nt[0]) * nt[1] * nt[2];
  const std::size_t nbins = ntiles * tile_bins;  // keys of bins past the grid's edge stay empty

  const std::span<const double> in[3] = {x, y, z};
  const double inv2pi = 0.5 / std::numbers::pi;
  // Bins in the caller's order, then a counting sort by bin. The scratch
  // arrays are members: reused across calls, they cost no page faults.
  bin_.resize(m);
  bool non_finite = false;
#pragma omp parallel for num_threads(threads_) schedule(static) reduction(|| : non_finite)
  for (std::int64_t j = 0; j < static_cast<std::int64_t>(m); ++j) {
    std::uint32_t tile = 0, in_tile = 0;
    for (int d = 2; d >= 0; --d) {
      non_finite = non_finite || !std::isfinite(in[d][j]);
      const double v = fold(in[d][j] * inv2pi, fine_[d]);
      const auto bd = static_cast<std::uint32_t>(std::min(nb[d] - 1, static_cast<int>(v * (1.0 / kBin[d]))));
      tile = tile * static_cast<std::uint32_t>(nt[d]) + bd / kTile;
      in_tile = in_tile * kTile + bd % kTile;
    }
    bin_[j] = tile * tile_bins + in_tile;
  }
  if (non_finite) {  // nothing but the scratch bins changed: the previous points stay set
    std::size_t j = 0;
    while (std::isfinite(x[j]) && std::isfinite(y[j]) && std::isfinite(z[j])) ++j;
    throw std::invalid_argument("set_points: point " + std::to_string(j) + " has a non-finite coordinate (" +
                                std::to_string(x[j]) + ", " + std::to_string(y[j]) + ", " + std::to_string(z[j]) +
                                "); coordinates must be finite (radians, any real value)");
  }
  std::vector<std::size_t> start(nbins + 1, 0);
  for (std::size_t j = 0; j < m; ++j) ++start[bin_[j] + 1];
  for (std::size_t b = 0; b < nbins; ++b) start[b + 1] += start[b];
  // Subproblems: the points of each tile, in pieces of at most max_sub_.
  // Slabs: runs of whole tile layers (tiles are ordered z-slowest), each at
  // least a kernel width thick, an even number of them or a single one (see
  // spread()); slab_sub_[k] is the first subproblem of slab k.
  const int layer_cells = kTile * kBin[2];
  const int layers_per_slab = (poly_.spec.width + layer_cells - 1) / layer_cells;
  int slabs = fine_[2] / (layers_per_slab * layer_cells);  // the last slab takes the rest
  if (slabs % 2 == 1) --slabs;
  if (slabs < 2) slabs = 1;
  const std::size_t tiles_per_layer = static_cast<std::size_t>(nt[0]) * nt[1];
  sub_begin_.clear();
  slab_sub_.assign(static_cast<std::size_t>(slabs) + 1, 0);
  for (std::size_t t = 0; t < ntiles; ++t) {
    const std::size_t layer = t / tiles_per_layer;
    if (layer % layers_per_slab == 0 && t % tiles_per_layer == 0) {
      const std::size_t k = layer / layers_per_slab;
      if (k > 0 && k < static_cast<std::size_t>(slabs)) slab_sub_[k] = sub_begin_.size();
    }
    for (std::size_t s = start[t * tile_bins]; s < start[(t + 1) * tile_bins]; s += static_cast<std::size_t>(max_sub_))
      sub_begin_.push_back(s);
  }
  slab_sub_[slabs] = sub_begin_.size();
  sub_begin_.push_back(m);
  // One scattered write per point (coordinates, folded again, and index
  // together; the kernels read them in this form): cheaper than scattering
  // indices and gathering three coordinate arrays through them.
  points_.resize(m);
  for (std::size_t j = 0; j < m; ++j)
    points_[start[bin_[j]]++] = {
        {fold(x[j] * inv2pi, fine_[0]), fold(y[j] * inv2pi, fine_[1]), fold(z[j] * inv2pi, fine_[2])},
        static_cast<std::int64_t>(j)};
}

void Spreader::spread(const double* c, int nc, double* grid, std::size_t pitch) const {
  if (nc != 1 && nc != 2) throw std::invalid_argument("Spreader::spread: nc must be 1 or 2");
  const std::int64_t nsub = static_cast<std::int64_t>(sub_begin_.size()) - 1;
  if (nsub <= 0) return;
  const int w = poly_.spec.width;
  const int n0 = fine_[0], n1 = fine_[1], n2 = fine_[2];
  const std::size_t row_pitch = pitch == 0 ? static_cast<std::size_t>(n0) : pitch;
  if (row_pitch < static_cast<std::size_t>(n0))
    throw std::invalid_argument("Spreader::spread: row pitch " + std::to_string(pitch) + " is shorter than a row of " +
                                std::to_string(n0) + " cells; it must be 0 (rows packed) or >= " + std::to_string(n0));

  // Strengths are read in the caller's order inside the spreading loop, each
  // prefetched a few points ahead (spreader_kernels.inc): the random reads
  // land while earlier points are spread. (The separate gather into sorted
  // order this replaces cost 10-25 ms more per type 1 of 10^6 points at
  // N = 64^3, eps = 1e-6: measured interleaved, bench/RESULTS.md.)

  // A slab's subgrids reach at most half a kernel width beyond it; slabs of
  // the same parity are separated by a slab at least a kernel width thick
  // (and their number is even, so the first and last slab, neighbours across
  // the period, differ in parity): the even slabs are spread in parallel,
  // then the odd ones, each slab by one thread, with plain adds. The order
  // in which a grid cell receives its contributions (parity, slab,
  // subproblem, point) does not depend on the thread count: the result is
  // bitwise the same with any number of threads.
  const int W = w, NC = nc;
  const std::int64_t slabs = static_cast<std::int64_t>(slab_sub_.size()) - 1;
  for (int parity = 0; parity < (slabs >= 2 ? 2 : 1); ++parity) {
#pragma omp parallel num_threads(slabs >= 2 ? threads_ : 1)
    {
      std::vector<double> sub;
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t k = parity; k < slabs; k += 2)
        for (std::size_t p = slab_sub_[k]; p < slab_sub_[k + 1]; ++p) {
          const std::size_t b = sub_begin_[p], e = sub_begin_[p + 1];
          int lo[3] = {INT_MAX, INT_MAX, INT_MAX}, hi[3] = {INT_MIN, INT_MIN, INT_MIN};
          for (std::size_t s = b; s < e; ++s) {
            const double* u = points_[s].u;
            const int l[3] = {first_node(u[0], W), first_node(u[1], W), first_node(u[2], W)};
            for (int d = 0; d < 3; ++d) {
              lo[d] = std::min(lo[d], l[d]);
              hi[d] = std::max(hi[d], l[d]);
            }
          }
          const int s0 = arithmetic().row_cells(hi[0] - lo[0], W, NC), s1 = hi[1] - lo[1] + W, s2 = hi[2] - lo[2] + W;
          sub.assign(static_cast<std::size_t>(s0) * s1 * s2 * NC, 0.0);
          detail::SpreadTask task{&poly_, points_.data(), c, b, e, {lo[0], lo[1], lo[2]}, s0, s1, sub.data()};
          arithmetic().spread(W, NC, task);
          // Add the subgrid into the periodic fine grid, each row in at most a
          // few contiguous pieces (it wraps around at most once per period).
          const int x0 = ((lo[0] % n0) + n0) % n0;
          for (int zz = 0; zz < s2; ++zz) {
            const int gz = ((lo[2] + zz) % n2 + n2) % n2;
            for (int yy = 0; yy < s1; ++yy) {
              const int gy = ((lo[1] + yy) % n1 + n1) % n1;
              double* grow = grid + NC * ((static_cast<std::size_t>(gz) * n1 + gy) * row_pitch);
              const double* srow = sub.data() + NC * ((static_cast<std::size_t>(zz) * s1 + yy) * s0);
              for (int i = 0, gx = x0; i < s0;) {
                const int len = std::min(s0 - i, n0 - gx);
                double* __restrict dst = grow + NC * gx;
                const double* src = srow + NC * i;
#pragma omp simd
                for (int q = 0; q < NC * len; ++q) dst[q] += src[q];
                i += len;
                gx = 0;
              }
            }
          }
        }
    }
  }
}

void Spreader::interpolate(const double* grid, double* c) const {
  const std::int64_t m = static_cast<std::int64_t>(points_.size());
  if (m == 0) return;
  const int n0 = fine_[0], n1 = fine_[1], n2 = fine_[2];
  const int w = poly_.spec.width;
  constexpr std::int64_t chunk = 4096;
  const std::int64_t chunks = (m + chunk - 1) / chunk;
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (std::int64_t q = 0; q < chunks; ++q) {
    const detail::InterpolateTask task{&poly_,
                                       points_.data(),
                                       grid,
                                       n0,
                                       n1,
                                       n2,
                                       static_cast<std::size_t>(q * chunk),
                                       static_cast<std::size_t>(std::min(m, (q + 1) * chunk)),
                                       c};
    arithmetic().interpolate(w, task);
  }
}

}  // namespace grains::correlation
