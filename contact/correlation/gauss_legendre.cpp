#include "contact/correlation/gauss_legendre.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace grains::correlation {

QuadratureRule gauss_legendre(int q) {
  if (q < 1) throw std::invalid_argument("gauss_legendre: need at least one node");
  QuadratureRule rule;
  rule.nodes.resize(q);
  rule.weights.resize(q);
  for (int i = 0; i < (q + 1) / 2; ++i) {
    // Initial guess (Tricomi): cos(pi (i + 3/4) / (q + 1/2)).
    double x = std::cos(std::numbers::pi * (i + 0.75) / (q + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;  // P_0, P_1
      for (int k = 2; k <= q; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      // P_q'(x) = q (x P_q - P_{q-1}) / (x^2 - 1)
      dp = q * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    rule.nodes[i] = -x;
    rule.nodes[q - 1 - i] = x;
    rule.weights[i] = w;
    rule.weights[q - 1 - i] = w;
  }
  return rule;
}

}  // namespace grains::correlation
