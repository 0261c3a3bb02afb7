#pragma once
// The "exponential of semicircle" (ES) spreading kernel of the non-uniform FFT,
//
//     phi(z) = exp(beta * (sqrt(1 - z^2) - 1)),   |z| <= 1,   0 otherwise,
//
// used in grid units as psi(t) = phi(2 t / w): it covers w fine-grid nodes.
// Its Fourier transform has no closed form; it is computed by Gauss–Legendre
// quadrature (the integrand is smooth inside and ~exp(-beta) at the ends).
//
// For speed the kernel values at the w nodes a point touches are evaluated as
// w piecewise polynomials in the point's fractional offset (one Horner pass
// for all w values, vectorisable), fitted once per plan at Chebyshev nodes.
//
// Parameters from the tolerance eps and the upsampling factor sigma: the
// aliasing error of the ES kernel decays like exp(-pi w sqrt(1 - 1/sigma)),
// so w = ceil(ln(1/eps) / (pi sqrt(1 - 1/sigma))) + 1 (+ 2 when sigma < 2) and
// beta = 0.98 pi (1 - 1/(2 sigma)) w (the bandwidth that balances aliasing
// against truncation, see docs/nfft.md for the measured accuracy).
#include <array>
#include <vector>

namespace grains::correlation {

inline constexpr int kMaxKernelWidth = 16;
inline constexpr int kMaxKernelDegree = 19;

struct KernelSpec {
  int width = 0;        // w: fine-grid nodes covered per dimension
  double beta = 0.0;    // shape parameter
  double sigma = 2.0;   // upsampling factor of the fine grid
};

// Kernel for tolerance eps in [1e-14, 1e-1] and upsampling sigma > 1. Throws
// std::invalid_argument when the pair needs w > kMaxKernelWidth.
KernelSpec choose_kernel(double eps, double sigma);

// Whether (eps, sigma) is achievable within kMaxKernelWidth.
bool kernel_feasible(double eps, double sigma);

// phi(z) for |z| <= 1, zero outside.
double es_kernel(double z, double beta);

// Fourier transform of psi in grid units, at integer mode k of a fine grid of
// n nodes: psi_hat(k) = int psi(t) cos(2 pi k t / n) dt. Returns the values
// for k = 0 .. kmax (psi_hat is even in k).
std::vector<double> kernel_fourier_series(const KernelSpec& spec, int n, int kmax);

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
