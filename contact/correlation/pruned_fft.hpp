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

// The real-to-complex 3D FFT of the ball spectra and the complex-to-real one
// of field synthesis, in FFTW's in-place layout (x fastest, each real row
// padded to 2 h0 doubles, h0 = n0/2 + 1; after the forward transform row
// (y, z) holds the complex modes m0 = 0 .. h0-1), as stages of batched 1D
// FFTs like PrunedFft3d: x on every row, y only on the columns m0 <= K0 of
// every plane, z only on the (m0 <= K0, |m1| <= K1) columns. Measured against
// one FFTW_ESTIMATE 3D plan: bench/RESULTS.md.
class PrunedRealFft3d {
 public:
  // n: the real grid; K: the modes needed per axis (m0 in [0, K0], |m_d| <= K_d
  // for d = 1, 2; modes past a grid's Nyquist are folded by the caller). K0
  // and K1 choose the lines; every z line of a needed column is transformed
  // whole, so K2 selects nothing.
  // `data` (2 h0 n1 n2 doubles) is used for planning only.
  PrunedRealFft3d(std::array<int, 3> n, std::array<int, 3> K, double* data, int threads, unsigned flags);

  // Real grid -> half spectrum, exponent sign -1; only the needed modes are
  // correct afterwards.
  void forward(double* data);
  // Half spectrum -> real grid, exponent sign +1, unnormalised; the input must
  // be zero outside the needed modes.
  void backward(double* data);

 private:
  using Complex = std::complex<double>;
  void stage_y(Complex* g, int s);
  void stage_z(Complex* g, int s);

  std::array<int, 3> n_;
  int h0_;
  int threads_;
  std::vector<int> xs_, ys_;      // needed complex columns in x and y
  FftwPlan rx_, cx_;              // rows: r2c, c2r
  FftwPlan py_[2], pz_[2];        // [0]: sign -1, [1]: sign +1
  std::vector<FftwBuffer> buf_;   // one per thread
};

}  // namespace grains::correlation
