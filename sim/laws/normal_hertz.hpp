#pragma once
// Normal slot: Hertz elastic force with viscous damping calibrated to the
// target restitution (restitution.hpp), clamped at zero so that an
// uncohesive contact never pulls:
//   F_n = max(0, K d^{3/2} + a sqrt(m* K) d^{1/4} d_dot),   K = 4/3 E* sqrt(R*).
// Case-file keys: materials[].restitution, youngs_modulus, poisson_ratio.
#include <algorithm>
#include <cmath>

#include "sim/laws/pair_params.hpp"

namespace grains::sim {

struct NormalState {
  double force;      // clamped normal force magnitude (>= 0), acts on i along +n
  double sqrt_Rd;    // sqrt(R* d), the Hertz contact radius
  double stiffness;  // tangent stiffness S_n = 2 E* sqrt(R* d)
};

struct HertzNormal {
  /// d: overlap; d_dot: rate of overlap (approach > 0); R: effective radius; m: effective mass.
  static inline NormalState evaluate(double d, double d_dot, double R, double m, const PairParams& p) {
    const double sqrt_Rd = std::sqrt(R * d);
    const double K = (4.0 / 3.0) * p.E_eff * std::sqrt(R);
    const double sqrt_d = std::sqrt(d);
    const double elastic = K * d * sqrt_d;
    const double viscous = p.damping * std::sqrt(m * K) * std::sqrt(sqrt_d) * d_dot;
    return {std::max(0.0, elastic + viscous), sqrt_Rd, 2.0 * p.E_eff * sqrt_Rd};
  }
};

}  // namespace grains::sim
