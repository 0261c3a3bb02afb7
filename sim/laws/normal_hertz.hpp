#pragma once
#include "contact/contact_geometry.hpp"
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
  double damping_scale;  // sqrt(m* K d^{1/2}); the normal damping coefficient is a times this
};

struct HertzNormal {
  /// d: overlap; d_dot: rate of overlap (approach > 0); R: effective radius; m: effective mass.
  /// Three square roots per contact: sqrt(R), sqrt(d) and the damping scale.
  static GRAINS_INLINE NormalState evaluate(double d, double d_dot, double R, double m, const PairParams& p) {
    const double sR = std::sqrt(R), sd = std::sqrt(d);
    const double sqrt_Rd = sR * sd;
    const double K = (4.0 / 3.0) * p.E_eff * sR;
    const double scale = std::sqrt(m * K * sd);  // = sqrt(m* K) d^{1/4}
    const double f = K * d * sd + p.damping * scale * d_dot;
    return {f > 0 ? f : 0.0, sqrt_Rd, 2.0 * p.E_eff * sqrt_Rd, scale};
  }
};

}  // namespace grains::sim
