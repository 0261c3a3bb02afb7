#pragma once
// The spreading kernel of the non-uniform FFT: the prolate spheroidal wave
// function of order zero,
//
//     phi(z) = psi_0(c, z) / psi_0(c, 0),   |z| <= 1,   0 otherwise,
//
// used in grid units as psi(t) = phi(2 t / w): it covers w fine-grid nodes.
// Among functions supported on [-1, 1] it concentrates the most energy in
// the band |xi| <= c / (2 pi) (Slepian and Pollak 1961), which is what the
// NUFFT's aliasing error measures; the exponential of semicircle and the
// Kaiser–Bessel kernel are closed-form approximations of it. psi_0 is
// computed once per kernel from its Legendre expansion, the eigenvector of the
// smallest eigenvalue of a symmetric tridiagonal matrix (Xiao, Rokhlin and
// Yarvin 2001); its Fourier transform, which has no closed form, by
// Gauss–Legendre quadrature.
//
// For speed the kernel values at the w nodes a point touches are evaluated as
// w piecewise polynomials in the point's fractional offset (one Horner pass
// for all w values, vectorisable), fitted once per plan at Chebyshev nodes.
//
// Parameters from the tolerance eps and the upsampling factor sigma: the
// width w is the smallest whose *predicted* error (predicted_error below) is
// at most 0.8 eps, with the bandwidth c = f pi (1 - 1/(2 sigma)) w and f in
// {0.97, 0.98, 0.99, 1.0} the one that predicts the smallest error
// (docs/nfft.md). The error of one point depends on its offset from the
// fine grid; what eps bounds is chosen by an ErrorModel.
#include <array>
#include <vector>

namespace grains::correlation {

inline constexpr int kMaxKernelWidth = 16;
inline constexpr int kMaxKernelDegree = 19;

// What the tolerance bounds.
enum class ErrorModel {
  // The relative l2 error of a transform of points in general position (the
  // offsets from the fine grid spread out): what a NUFFT's tolerance means
  // (type 1 and 2 of Nufft3d).
  general_position,
  // The error of every point at its worst offset: points on a lattice
  // commensurate with the fine grid (up to ~3x the first; the overlap fields,
  // whose tolerances are maximum errors, use this one).
  worst_offset,
};

struct KernelSpec {
  int width = 0;        // w: fine-grid nodes covered per dimension
  double beta = 0.0;    // bandwidth parameter c of psi_0(c, z)
  double sigma = 2.0;   // upsampling factor of the fine grid
};

// Kernel for tolerance eps in [1e-14, 1e-1] and upsampling sigma > 1. Throws
// std::invalid_argument when the pair needs w > kMaxKernelWidth. Results are
// cached per (eps, sigma, model); thread-safe.
KernelSpec choose_kernel(double eps, double sigma,
                         ErrorModel model = ErrorModel::general_position);

// Whether (eps, sigma) is achievable within kMaxKernelWidth.
bool kernel_feasible(double eps, double sigma,
                     ErrorModel model = ErrorModel::general_position);

// phi(z) of a kernel: the Legendre expansion of psi_0, evaluated by the
// three-term recurrence. The support is taken half-open, -1 <= z < 1, as the
// spreader sees it: a point exactly w/2 nodes right of a node touches it with
// the limit value psi_0(c, 1) / psi_0(c, 0) (not zero: the PSWF does not
// vanish at the ends) and not the node w/2 to its left.
class KernelFunction {
 public:
  explicit KernelFunction(const KernelSpec& spec);
  double operator()(double z) const;

 private:
  std::vector<double> coeff_;  // coefficient of P_{2k}(z), k = 0, 1, ...
  double scale_ = 1.0;         // 1 / psi_0(c, 0)
};

// Fourier transform of psi in grid units, at integer mode k of a fine grid of
// n nodes: psi_hat(k) = int psi(t) cos(2 pi k t / n) dt. Returns the values
// for k = 0 .. kmax (psi_hat is even in k).
std::vector<double> kernel_fourier_series(const KernelSpec& spec, int n, int kmax);

// Predicted relative error of a 3D transform with this kernel on a fine
// grid of sigma N nodes per dimension, for random strengths: the error of
// spreading one point and deconvolving, at mode k and offset x from the grid,
//     e(k, x) = sum_l psi(x - l) exp(-2 pi i k (x - l) / n) / psi_hat(k) - 1
// (the aliasing sum plus the kernel's truncation), is averaged in square over
// the modes |k| / n <= 1 / (2 sigma) and over x in [0, 1)
// (general_position) or taken at the worst x for each k (worst_offset); the
// three dimensions' errors add in square for points in general position,
// sqrt(3 <|e|^2>), and are bounded by 3 sqrt(<|e|^2>) for points at the same
// worst offset in all three (Cauchy–Schwarz). The unit tests compare it with
// measured errors.
double predicted_error(const KernelSpec& spec,
                       ErrorModel model = ErrorModel::general_position);

// Piecewise-polynomial form: for a point with fractional offset v in [0, 1)
// (v = l0 - u + w/2 where l0 is the first node touched), the value at node
// l0 + i is  sum_p coeff[p][i] x^p  with x = 2 v - 1.
struct KernelPolynomial {
  KernelSpec spec;
  int degree = 0;
  // coeff[p * kMaxKernelWidth + i]
  std::array<double, (kMaxKernelDegree + 1) * kMaxKernelWidth> coeff{};
};

KernelPolynomial fit_kernel_polynomial(const KernelSpec& spec);

// Values at the w nodes by Horner, out[0..w-1]. Generic (runtime width) form,
// used by tests; the spreader has compile-time-width copies of this loop.
void eval_kernel_polynomial(const KernelPolynomial& kp, double v, double* out);

}  // namespace grains::correlation
