#pragma once
// The fine-grid FFT of the NUFFT, done as three stages of batched 1D FFTs that
// skip the lines the transform does not need.
//
// Type 1 needs only the N_d lowest frequencies of each dimension out of n_d:
// after the x-stage (every row), the y-stage transforms only the N_0 needed
// x-columns of each z-plane, and the z-stage only the N_0 x N_1 needed
// (x, y)-columns: (1 + N0/n0 + N0 N1/(n0 n1)) / 3 of the full work, 58 % at
// upsampling 2. Type 2 starts from a grid that is zero outside those modes and
// runs the same stages backwards (z on the needed columns, y on the needed
// x-columns of every plane, x on every row).
//
// Strided lines are first copied (blocked transpose) into a per-thread
// contiguous buffer and transformed there: FFTW_ESTIMATE plans of a whole 3D
// grid stride through memory at the grid's power-of-two pitch and run 4x
// slower at 256^3 (measured, docs/nfft.md). Stages run plane by plane in
// parallel; each line is transformed by the same plan whatever the thread
// count, so results do not depend on it.
#include <array>
#include <complex>
#include <vector>

#include "contact/correlation/fftw_util.hpp"

namespace grains::correlation {

class PrunedFft3d {
 public:
  // fine: grid n (x fastest, complex); modes: N_d <= n_d, the needed
  // frequencies k = -floor(N/2) .. ceil(N/2)-1 (fine index k mod n).
  // The grid's x-rows are `pitch` >= n0 complex values apart in memory (the
  // planes pitch * n1). `grid` is the array the transforms will run on (used
  // for planning only; FFTW_ESTIMATE does not touch it).
  PrunedFft3d(std::array<int, 3> fine, std::array<int, 3> modes, int pitch, fftw_complex* grid, int threads,
              unsigned flags);

  // In place, exponent sign -1 or +1. Forward-pruned: every input line, only
  // the needed modes of the output are correct (type 1).
  void forward_pruned(fftw_complex* grid, int sign);
  // Input zero outside the needed modes; the whole output is correct (type 2).
  void backward_pruned(fftw_complex* grid, int sign);

 private:
  using Complex = std::complex<double>;
  void stage_x(Complex* g, int sign);
  void stage_y(Complex* g, int sign);
  void stage_z(Complex* g, int sign);

  std::array<int, 3> n_;
  std::array<int, 3> modes_;
  int pitch_;
  int threads_;
  std::vector<int> xs_, ys_;           // needed fine indices in x and y
  FftwPlan px_[2], py_[2], pz_[2];     // [0]: sign -1, [1]: sign +1
  std::vector<FftwBuffer> buf_;        // one per thread: N0 lines of max(n1, n2)
};

}  // namespace grains::correlation
