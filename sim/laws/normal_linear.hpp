#pragma once
// Normal slot: the linear spring-dashpot of Cundall & Strack (1979),
//   F_n = k_n d + gamma_n d_dot      (d: overlap, d_dot: approach rate),
// as LAMMPS's gran/hooke and LIGGGHTS's hooke define it. The stiffness is
// given (stiffness), or derived per contact from a contact time t_c and the
// restitution e, k_n = m* (pi^2 + ln^2 e) / t_c^2, so that every contact
// lasts t_c whatever its mass, or from a characteristic impact velocity V as
// LIGGGHTS does, k_n = 16/15 sqrt(R*) E* (15 m* V^2 / (16 sqrt(R*) E*))^(1/5)
// (the stiffness whose peak overlap at V equals Hertz's). The damping is
// given (damping, or damping_rate x m* as LAMMPS's gran/hooke gamma_n, with
// stiffness only) or derived from the pair's
// restitution, gamma_n = 2 sqrt(m* k_n) (-ln e) / sqrt(pi^2 + ln^2 e), so
// that the oscillator's restitution is e exactly and a contact lasts
//   t_c = pi / sqrt(k_n/m* - (gamma_n / 2 m*)^2).
// Like its peers the force is not clamped by default: near the end of a
// damped contact it pulls a little, which is what makes e and t_c exact
// (limit_force: true clamps it at zero, as LIGGGHTS's limitForce; the
// restitution is then higher than e). It pairs with a linear tangential
// spring k_t = kappa k_n and dashpot gamma_t = x gamma_n (LAMMPS
// gran/hooke/history defaults kappa = 2/7, x = 1/2), Coulomb-limited by the
// tangential slot. Registered in normal_laws.hpp.
#include <cmath>
#include <string>
#include <vector>

#include "sim/laws/law_values.hpp"
#include "sim/laws/material.hpp"
#include "sim/laws/normal_state.hpp"
#include "sim/laws/step_scale.hpp"
#include "sim/keys/effect_doc.hpp"

namespace grains::sim {

/// The normal state of a linear contact (normal_state.hpp).
struct LinearState {
  double force;  // unclamped unless limit_force
  double load;   // max(0, force)
  double kn, gn;  // this contact's k_n and gamma_n
  double kappa, x;  // k_t / k_n, gamma_t / gamma_n
  GRAINS_INLINE double stiffness(const PairParams&) const { return kn; }
  GRAINS_INLINE double damping(const PairParams&) const { return gn; }
  GRAINS_INLINE double tangential_stiffness(const PairParams&) const { return kappa * kn; }
  GRAINS_INLINE double tangential_damping(const PairParams&) const { return x * gn; }
};

struct LinearNormal {
  static constexpr const char* name = "linear";
  static constexpr const char* tangential_name = "linear";
  // Keys, in LawValues order.
  enum Key { kStiffness, kDamping, kContactTime, kVelocity, kKappa, kX, kLimit, kRate };
  // The prepared per-pair constants in PairParams::normal.
  enum Slot { sMode, sK, sA, sB, sGamma, sG1, sKappa, sX, sLimit, sRate };
  static constexpr double Stiffness = 0, ContactTime = 1, Velocity = 2;  // sMode

  static std::string summary() {
    return "Linear spring-dashpot (Cundall-Strack), F = k_n d + gamma_n d_dot, as LAMMPS's and LIGGGHTS's hooke: "
           "give one of stiffness, contact_time or characteristic_velocity; the damping is derived from "
           "materials[].restitution (exact for the unclamped law) unless given. Pairs with the linear tangential "
           "spring k_t = tangential_stiffness_ratio k_n, gamma_t = tangential_damping_ratio gamma_n.";
  }
  static std::vector<KeySpec> keys() {
    const double inf = std::numeric_limits<double>::infinity();
    using K = KeyType;
    return {key("stiffness", K::Number, "normal spring stiffness k_n").si("N/m").in(0, inf, true),
            key("damping", K::Number,
                "normal dashpot gamma_n (with stiffness only); default: from the pair's restitution")
                .si("N s/m")
                .in(0, inf),
            key("contact_time", K::Number,
                "duration of every contact t_c; k_n and gamma_n follow per contact from t_c, m* and restitution")
                .si("s")
                .in(0, inf, true),
            key("characteristic_velocity", K::Number,
                "LIGGGHTS's hooke: k_n from E*, R*, m* and this impact speed (same peak overlap as Hertz)")
                .si("m/s")
                .in(0, inf, true),
            key("tangential_stiffness_ratio", K::Number, "k_t / k_n of the paired tangential spring")
                .def(2.0 / 7.0)
                .in(0, inf),
            key("tangential_damping_ratio", K::Number, "gamma_t / gamma_n of the paired tangential dashpot")
                .def(0.5)
                .in(0, inf),
            key("limit_force", K::Bool,
                "clamp the normal force at zero (no pull while unloading; restitution then above the target)")
                .def_bool(false),
            key("damping_rate", K::Number,
                "normal dashpot per unit effective mass, gamma_n = m* x damping_rate (with stiffness only; "
                "LAMMPS's gran/hooke gamma_n)")
                .si("1/s")
                .in(0, inf)};
  }

  /// One set of valid values per way of giving the law (defaults filled in).
  static std::vector<LawValues> examples() {
    const LawValues d = law_defaults<LinearNormal>();
    auto with = [&](std::initializer_list<std::pair<Key, double>> kv) {
      LawValues v = d;
      for (const auto& [key, value] : kv) v[key] = value;
      return v;
    };
    return {with({{kStiffness, 1e5}}), with({{kStiffness, 1e5}, {kDamping, 2.0}}), with({{kContactTime, 2e-4}}),
            with({{kVelocity, 1.0}}), with({{kStiffness, 1e5}, {kLimit, 1}, {kKappa, 1.0}, {kX, 1.0}}),
            with({{kStiffness, 1e5}, {kRate, 50.0}})};
  }

  /// "" when the values (defaults filled in) define the law, else what is wrong.
  static std::string check(const LawValues& v) {
    const int given = v.given(kStiffness) + v.given(kContactTime) + v.given(kVelocity);
    if (given != 1)
      return "give exactly one of stiffness, contact_time or characteristic_velocity (" + std::to_string(given) +
             " given)";
    if (v.given(kDamping) && !v.given(kStiffness))
      return "damping goes with stiffness; with contact_time or characteristic_velocity it follows from the "
             "restitution";
    if (v.given(kRate) && !v.given(kStiffness))
      return "damping_rate goes with stiffness; with contact_time or characteristic_velocity the damping "
             "follows from the restitution";
    if (v.given(kRate) && v.given(kDamping)) return "give damping or damping_rate, not both";
    return {};
  }

  static std::string prepare(PairParams& p, const LawValues& v) {
    if (auto e = check(v); !e.empty()) return e;
    auto& c = p.normal;
    const double le = p.restitution < 1 ? std::log(p.restitution) : 0.0;
    const double pl = M_PI * M_PI + le * le;
    c[sMode] = v.given(kStiffness) ? Stiffness : v.given(kContactTime) ? ContactTime : Velocity;
    c[sK] = v.given(kStiffness) ? v[kStiffness] : v.given(kContactTime) ? pl / (v[kContactTime] * v[kContactTime]) : 0;
    c[sA] = 16.0 / 15.0 * p.E_eff;
    c[sB] = v.given(kVelocity) ? 15.0 * v[kVelocity] * v[kVelocity] / (16.0 * p.E_eff) : 0;
    c[sGamma] = v.given(kDamping) ? v[kDamping] : -1;
    c[sG1] = 2.0 * -le / std::sqrt(pl);
    c[sKappa] = v[kKappa];
    c[sX] = v[kX];
    c[sLimit] = v[kLimit] != 0 ? 1 : 0;
    c[sRate] = v.given(kRate) ? v[kRate] : -1;
    return {};
  }

  /// k_n and gamma_n of one contact.
  static GRAINS_INLINE void coefficients(double R, double m, const PairParams& p, double& kn, double& gn) {
    const auto& c = p.normal;
    if (c[sMode] == Stiffness) {
      kn = c[sK];
    } else if (c[sMode] == ContactTime) {
      kn = c[sK] * m;
    } else {
      const double sR = std::sqrt(R);
      kn = c[sA] * sR * std::pow(c[sB] * m / sR, 0.2);
    }
    gn = c[sGamma] >= 0 ? c[sGamma] : c[sRate] >= 0 ? c[sRate] * m : c[sG1] * std::sqrt(m * kn);
  }

  static GRAINS_INLINE LinearState evaluate(double d, double d_dot, double R, double m, const PairParams& p) {
    double kn, gn;
    coefficients(R, m, p, kn, gn);
    const double f = kn * d + gn * d_dot;
    const double load = f > 0 ? f : 0.0;
    return {p.normal[sLimit] != 0 ? load : f, load, kn, gn, p.normal[sKappa], p.normal[sX]};
  }

  /// The contact time t_c = pi / sqrt(k_n/m* - (gamma_n/2m*)^2) of the
  /// stiffest pair of the lightest grains (m* = m/2, R* = r/2; undamped when
  /// the dashpot is overcritical). Verlet is stable below 2/omega = 0.64 t_c
  /// undamped; a step above t_c/pi is refused, above t_c/20 warned about.
  static StepScale step_scale(const PairTable& t, const GrainExtremes& g) {
    double tc = std::numeric_limits<double>::infinity();
    const double m = 0.5 * g.min_mass, R = 0.5 * g.min_radius;
    for (int a = 0; a < t.size(); ++a)
      for (int b = 0; b < t.size(); ++b) {
        double kn, gn;
        coefficients(R, m, t(a, b), kn, gn);
        const double w2 = kn / m - (gn / (2 * m)) * (gn / (2 * m));
        if (kn > 0 && m > 0) tc = std::min(tc, M_PI / std::sqrt(w2 > 0 ? w2 : kn / m));
      }
    return {tc, "contact times", "t_c", 1.0 / M_PI, 0.05};
  }
};

}  // namespace grains::sim
