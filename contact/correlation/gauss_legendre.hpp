#pragma once
// Gauss–Legendre quadrature nodes and weights on [-1, 1], used to compute the
// Fourier transform of the spreading kernel (the prolate spheroidal wave
// function has no closed form).
#include <vector>

namespace grains::correlation {

struct QuadratureRule {
  std::vector<double> nodes;
  std::vector<double> weights;
};

// q-point rule, exact for polynomials of degree 2q-1. Nodes by Newton's method
// on the three-term recurrence of P_q, started from Chebyshev-like guesses.
QuadratureRule gauss_legendre(int q);

}  // namespace grains::correlation
