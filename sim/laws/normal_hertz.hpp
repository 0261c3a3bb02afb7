#pragma once
// Normal slot: Hertz elastic force with viscous damping calibrated to the
// target restitution (restitution.hpp), clamped at zero so that an
// uncohesive contact never pulls:
//   F_n = max(0, K d^{3/2} + a sqrt(m* K) d^{1/4} d_dot),   K = 4/3 E* sqrt(R*).
// It pairs with Mindlin's tangential spring k_t = 8 G* sqrt(R* d), damped as
// the normal spring is: eta_t = a sqrt(2/3) sqrt(m* k_t).
// Case-file keys: materials[].youngs_modulus, poisson_ratio, restitution
// (no keys of its own). Registered in normal_laws.hpp.
#include <cmath>
#include <string>
#include <vector>

#include "sim/laws/law_values.hpp"
#include "sim/laws/normal_state.hpp"
#include "sim/laws/pair_params.hpp"
#include "sim/laws/restitution.hpp"
#include "sim/laws/step_scale.hpp"
#include "sim/keys/effect_doc.hpp"

namespace grains::sim {

/// The normal state of a Hertz contact (normal_state.hpp).
struct HertzState {
  double force;    // Hertz: clamped, >= 0 (DMT, normal_dmt.hpp, less its attraction)
  double load;     // Hertz: = force (DMT: plus its attraction)
  double sqrt_Rd;  // sqrt(R* d), the Hertz contact radius
  double scale;    // sqrt(m* K d^{1/2}): the normal damping coefficient is a times this
  GRAINS_INLINE double stiffness(const PairParams& p) const { return 2.0 * p.E_eff * sqrt_Rd; }
  GRAINS_INLINE double damping(const PairParams& p) const { return p.damping * scale; }
  /// Mindlin: k_t = 8 G* sqrt(R* d).
  GRAINS_INLINE double tangential_stiffness(const PairParams& p) const { return 8.0 * p.G_eff * sqrt_Rd; }
  /// eta_t = a sqrt(2/3) sqrt(m k_t) = a 2 sqrt(G*/E*) sqrt(m K d^{1/2}) (no extra square root).
  GRAINS_INLINE double tangential_damping(const PairParams& p) const {
    return p.damping * p.tangential_damping_ratio * scale;
  }
};

struct HertzNormal {
  static constexpr const char* name = "hertz";
  /// The name of the tangential spring it pairs with (contact.tangential).
  static constexpr const char* tangential_name = "mindlin";
  static std::string summary() {
    return "Hertz elastic force K d^(3/2), K = 4/3 E* sqrt(R*), with viscous damping calibrated so that the "
           "achieved restitution equals materials[].restitution exactly; clamped at zero (no attraction without "
           "cohesion). Pairs with Mindlin's tangential spring 8 G* sqrt(R* d). Reads youngs_modulus, poisson_ratio "
           "and restitution of the materials; no keys of its own.";
  }
  static std::vector<KeySpec> keys() { return {}; }
  static std::string check(const LawValues&) { return {}; }
  static std::vector<LawValues> examples() { return {LawValues{}}; }

  /// Per material pair, once at set-up: the damping that achieves the
  /// pair's restitution, and the ratio of the tangential to the normal
  /// damping scale. Returns an error text, or "" when the values are valid.
  static std::string prepare(PairParams& p, const LawValues&) {
    p.damping = damping_for_restitution(p.restitution);
    p.tangential_damping_ratio = 2.0 * std::sqrt(p.G_eff / p.E_eff);
    return {};
  }

  /// d: overlap; d_dot: rate of overlap (approach > 0); R: effective radius; m: effective mass.
  /// Three square roots per contact: sqrt(R), sqrt(d) and the damping scale.
  static GRAINS_INLINE HertzState evaluate(double d, double d_dot, double R, double m, const PairParams& p) {
    const double sR = std::sqrt(R), sd = std::sqrt(d);
    const double sqrt_Rd = sR * sd;
    const double K = (4.0 / 3.0) * p.E_eff * sR;
    const double scale = std::sqrt(m * K * sd);  // = sqrt(m* K) d^{1/4}
    const double f = K * d * sd + p.damping * scale * d_dot;
    const double fc = f > 0 ? f : 0.0;
    return {fc, fc, sqrt_Rd, scale};
  }

  /// The time scale a step is compared with: the Rayleigh time of the
  /// smallest grain. Above 1 T_R contacts are unresolved; above 0.3 T_R their
  /// accuracy suffers.
  static StepScale step_scale(const PairTable&, const GrainExtremes& g) {
    return {g.rayleigh_time, "Rayleigh times", "T_R", 1.0, 0.3, true};
  }
};

}  // namespace grains::sim
