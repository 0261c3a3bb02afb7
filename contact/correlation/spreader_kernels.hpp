#pragma once
// The arithmetic core of spreading and interpolation, compiled three times:
// for the baseline instruction set (spreader.cpp), with AVX2 + FMA
// (spreader_avx2.cpp) and with AVX-512 (spreader_avx512.cpp; both x86-64
// only), chosen at run time by the CPU (spreader.cpp). All copies see the
// same source (spreader_kernels.inc);
// the tasks below are plain data so that no inline library template is
// instantiated in the AVX2 or AVX-512 unit (the linker could otherwise keep
// that unit's copy for the baseline code as well).
#include <cstddef>
#include <cstdint>

#include "contact/correlation/spreading_kernel.hpp"

namespace grains::correlation::detail {

// A point in sorted order: fine-grid coordinates and the caller's index.
struct SortedPoint {
  double u[3];
  std::int64_t index;
};

// Spread points [begin, end) (sorted order) into a zeroed subgrid of
// s0 x s1 x s2 cells (nc doubles each) whose first node is lo.
struct SpreadTask {
  const KernelPolynomial* kernel;
  const SortedPoint* pts;
  const double* c;  // strengths, nc per point, in the caller's order (pts[s].index)
  std::size_t begin, end;
  int lo[3];
  int s0, s1;
  double* sub;
};

// c_out[2 pts[s].index] (+1) = interpolation of the complex periodic fine grid
// (n0 x n1 x n2) at the sorted points [begin, end).
struct InterpolateTask {
  const KernelPolynomial* kernel;
  const SortedPoint* pts;
  const double* grid;
  int n0, n1, n2;
  std::size_t begin, end;
  double* c;
};

// Cells per subgrid row for a subproblem whose points' first nodes span
// `span` cells in x: W + span plus the room a copy's whole-vector row
// updates need (they touch it with +0).
int spread_row_cells_baseline(int span, int width, int nc);
void spread_baseline(int width, int nc, const SpreadTask& t);
void interpolate_baseline(int width, const InterpolateTask& t);
#if GRAINS_SPREAD_AVX2
int spread_row_cells_avx2(int span, int width, int nc);
void spread_avx2(int width, int nc, const SpreadTask& t);
void interpolate_avx2(int width, const InterpolateTask& t);
int spread_row_cells_avx512(int span, int width, int nc);
void spread_avx512(int width, int nc, const SpreadTask& t);
void interpolate_avx512(int width, const InterpolateTask& t);
#endif

}  // namespace grains::correlation::detail
