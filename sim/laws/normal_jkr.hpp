#pragma once
// Normal slot: JKR adhesion (Johnson, Kendall & Roberts, Proc. R. Soc. A
// 324, 1971; Johnson, Contact Mechanics, 1985, sec. 5.5) for soft or large
// sticky grains. In terms of the contact radius a (w: the pair's work of
// adhesion, E*, R* as for Hertz):
//   F = 4 E* a^3 / (3 R*) - sqrt(8 pi w E* a^3),   d = a^2 / R* - sqrt(2 pi w a / E*).
// Scaled by the load-controlled pull-off point, F_c = 3/2 pi w R*,
// a_c = (9 pi w R*^2 / (8 E*))^(1/3), d_c = a_c^2 / (3 R*), x = a / a_c:
//   F / F_c = x^3 - 2 x^(3/2),   d / d_c = 3 x^2 - 4 x^(1/2)
// (docs/dev/adhesion_sources.md). With u = sqrt(a) the overlap relation
// is a quartic in u whose largest root is the stable branch: a contact that
// has just formed takes it in closed form (Ferrari's resolvent cubic,
// evaluated without cancellation), a contact that holds by Halley's method
// from the last step's root, which it keeps as its contact state (one
// iteration in a bed; no cube root).
//
// Hysteresis: a contact forms when the surfaces touch (d >= 0, where the
// force jumps to -8/9 F_c) and then persists in tension, at negative
// overlap, down to the separation where the stable branch ends under
// displacement control, d_f = -3^(2/3) d_c (a = a_c / 3^(2/3), F = -5/9 F_c:
// the vertical tangent of the d(a) curve), where it snaps off. (LAMMPS's jkr
// lets go earlier, at d = -d_c where F = -F_c.) Whether a pair is in contact
// is that same double of history (0: not in contact), after the tangential
// and rolling springs'; the neighbour lists, ghosts and wall near lists
// reach d_f further (NeighborList::reach), so a stretched contact is never
// missed.
//
// Damping: the Hertz part's calibrated dashpot with the Hertz stiffness of
// the JKR contact radius, eta = a_damp sqrt(m* 4/3 E* a) (exactly Hertz's when
// w = 0, so the restitution without adhesion is the requested one; it never
// divides by the overlap). The repulsive part 4 E* a^3/(3R*) + eta d_dot is
// clamped at zero as Hertz's is, the adhesive part is not damped. The
// Coulomb and rolling limits scale with F_n + 2 F_c (Thornton 1991; Marshall,
// J. Comput. Phys. 228, 2009, eq. 43; LAMMPS's cohesive limit), Mindlin's
// tangential spring 8 G* a uses the JKR contact radius (Thornton & Yin,
// Powder Technol. 65, 1991). A pair with w = 0 is a Hertz contact, bit for
// bit. Registered in normal_laws.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "sim/laws/normal_hertz.hpp"

namespace grains::sim {

/// The JKR relations. With u = sqrt(a), the overlap relation is the quartic
///   u^4 - B u - A = 0,   A = R* d,   B = R* sqrt(2 pi w / E*),
/// whose largest root is the stable branch (it exists down to the break,
/// where the quartic has a double root at u^3 = B/4: the vertical tangent).
struct JkrCurve {
  /// 3^(2/3): the break d_f = -kBreak d_c (Johnson's scaled form below).
  static constexpr double kBreak = 2.0800838230519041;
  /// The largest root u of u^4 - B u - A = 0 (B > 0, A >= -3 (B/4)^(4/3)) in
  /// closed form: Ferrari's resolvent cubic y^3 + A y - B^2/8 = 0 by
  /// Cardano, s = sqrt(2 y), u = (s + sqrt(2 B / s - s^2)) / 2.
  static GRAINS_INLINE double root(double A, double B) {
    const double h = B * B * (1.0 / 16.0), q = A * (1.0 / 3.0);
    const double D = std::max(0.0, h * h + q * q * q);  // 0 exactly at the break
    const double t = std::cbrt(h + std::sqrt(D));     // y = t - q / t
    // (For A > 0 the difference cancels; with t' = -q/t, t^3 + t'^3 = 2 h, so y = 2 h / (t^2 - t t' + t'^2).)
    const double y = A > 0 ? 2.0 * h / (t * t + q + q * q / (t * t)) : t - q / t;
    const double s = std::sqrt(2.0 * y);
    return 0.5 * (s + std::sqrt(std::max(0.0, 2.0 * B / s - s * s)));
  }
  /// The same root by Halley's method from u on the stable branch (the last
  /// step's root: the overlap moved little, one iteration, two after a
  /// jolt). Cubic convergence: after a step du the root is within about
  /// 3 (du/u)^3 u, so a step below 1e-4 u is the last (1e-12 of u, ~1e-11
  /// of the force). Falls back to the closed form where f' vanishes (at the
  /// break, where the branch ends).
  static GRAINS_INLINE double root_from(double u, double A, double B) {
    for (int k = 0; k < 20; ++k) {
      const double u2 = u * u, u3 = u2 * u;
      const double f = u3 * u - B * u - A, fp = 4.0 * u3 - B;
      if (!(fp > 1e-6 * B)) return root(A, B);
      const double du = 2.0 * f * fp / (2.0 * fp * fp - 12.0 * f * u2);
      u -= du;
      if (std::abs(du) <= 1e-4 * u) return u;
    }
    return root(A, B);
  }
  /// Johnson's scaled form: x = a / a_c, a_c = (9 pi w R*^2 / (8 E*))^(1/3),
  /// F / F_c = x^3 - 2 x^(3/2), d / d_c = 3 x^2 - 4 x^(1/2), F_c = 3/2 pi w R*,
  /// d_c = a_c^2 / (3 R*) (in these units A = dh / 3, B = 4/3, u = sqrt(x)).
  static double x_of(double dh) {
    const double u = root(dh / 3.0, 4.0 / 3.0);
    return u * u;
  }
  static double force(double x) { return x * x * x - 2.0 * x * std::sqrt(x); }  // F / F_c
  static double overlap(double x) { return 3.0 * x * x - 4.0 * std::sqrt(x); }  // d / d_c
};

struct JkrNormal {
  static constexpr const char* name = "jkr";
  static constexpr const char* tangential_name = "mindlin";
  static constexpr bool adhesive = true;
  /// One double per contact: sqrt(a) of the last step while the pair is in
  /// contact (it may then be stretched to d_f), 0 when it is not: the
  /// contact state and Halley's starting point.
  static constexpr int history_size = 1;
  // PairParams::normal: 3/2 pi w; sqrt(2 pi w / E*); sqrt(8 pi w E*); 4/3 E*;
  // |d_f| / R*^(1/3) = 3/4 (pi^2 w^2 / E*^2)^(1/3), and its cube
  enum Slot { sFc, sC, sAdh, sK, sBreak, sBreak3 };

  static std::string summary() {
    return "JKR adhesion (Johnson-Kendall-Roberts 1971) for soft or large sticky grains: the force of the JKR "
           "contact radius, F = 4 E* a^3/(3 R*) - sqrt(8 pi w E* a^3), pull-off force 3/2 pi w R*, w the pair's "
           "work of adhesion (2 sqrt(g_a g_b) from materials[].surface_energy, or contact.pairs[].work_of_adhesion). "
           "Hysteretic: a contact forms on touching and holds in tension down to the separation "
           "-(3/4)(pi^2 w^2 R*/E*^2)^(1/3), where it snaps off (the neighbour lists reach that far). Damped as "
           "model: hertz with the Hertz stiffness of the JKR contact radius, so the restitution is exact without "
           "adhesion; the friction and rolling limits scale with F_n + 2 F_c; Mindlin's tangential spring 8 G* a. "
           "Spheres and clumps (not ellipsoids), integrator verlet.";
  }
  static std::vector<KeySpec> keys() { return {}; }
  static std::string check(const LawValues&) { return {}; }
  static std::vector<LawValues> examples() { return {LawValues{}}; }

  static std::string prepare(PairParams& p, const LawValues& v) {
    if (auto e = HertzNormal::prepare(p, v); !e.empty()) return e;
    const double w = p.work_of_adhesion, E = p.E_eff;
    p.normal[sFc] = 1.5 * M_PI * w;
    p.normal[sC] = std::sqrt(2.0 * M_PI * w / E);
    p.normal[sAdh] = std::sqrt(8.0 * M_PI * w * E);
    p.normal[sK] = 4.0 / 3.0 * E;
    p.normal[sBreak] = 0.75 * std::cbrt(M_PI * M_PI * w * w / (E * E));
    p.normal[sBreak3] = p.normal[sBreak] * p.normal[sBreak] * p.normal[sBreak];
    return {};
  }

  /// How far beyond touching (m) a contact of radius of curvature R may hold: |d_f|.
  static GRAINS_INLINE double reach(double R, const PairParams& p) { return p.normal[sBreak] * std::cbrt(R); }
  /// The farthest any pair of the table may hold, for radii of curvature up to R.
  template <class Table>  // PairTable (material.hpp)
  static double reach(const Table& t, double R) {
    double r = 0;
    for (int a = 0; a < t.size(); ++a)
      for (int b = 0; b < t.size(); ++b) r = std::max(r, reach(R, t(a, b)));
    return r;
  }

  /// Whether the pair is in contact at overlap d, given its state `u`
  /// (evaluate() keeps it): it forms on touching and lets go beyond d_f.
  static GRAINS_INLINE bool engaged(double d, double R, const PairParams& p, double& u) {
    if (d >= 0) return true;
    if (u > 0 && -d * d * d < p.normal[sBreak3] * R) return true;  // (-d < |d_f| without a cube root)
    u = 0.0;
    return false;
  }

  /// The normal state of an engaged contact; `u` is its state (0: it just touched).
  static GRAINS_INLINE HertzState evaluate(double d, double d_dot, double R, double m, const PairParams& p,
                                           double& u) {
    if (p.work_of_adhesion == 0) return HertzNormal::evaluate(d, d_dot, R, m, p);
    const double A = R * d, B = R * p.normal[sC];
    u = u > 0 ? JkrCurve::root_from(u, A, B) : JkrCurve::root(A, B);
    const double a = u * u;
    // 4 E* a^3 / (3 R*) = 4/3 E* a (d + c u), from the quartic (no division).
    const double scale = std::sqrt(m * p.normal[sK] * a);
    const double rep = std::max(0.0, p.normal[sK] * a * (d + p.normal[sC] * u) + p.damping * scale * d_dot);
    HertzState s;
    s.force = rep - p.normal[sAdh] * a * u;
    s.load = std::max(0.0, s.force + 2.0 * p.normal[sFc] * R);
    s.sqrt_Rd = a;
    s.scale = scale;
    return s;
  }

  /// The Rayleigh time, or the period of the adhesive neck when that is
  /// shorter: sqrt(m*/k0) of the smallest grains' contact at zero load (its
  /// stiffness k0 = 0.4762 F_c / d_c) for the stickiest pair.
  template <class Table>
  static StepScale step_scale(const Table& t, const GrainExtremes& g) {
    StepScale s = HertzNormal::step_scale(t, g);
    const double R = 0.5 * g.min_radius, m = 0.5 * g.min_mass;
    if (!(R > 0) || !(m > 0)) return s;
    double tn = std::numeric_limits<double>::infinity();
    for (int a = 0; a < t.size(); ++a)
      for (int b = 0; b < t.size(); ++b) {
        const PairParams& p = t(a, b);
        if (p.work_of_adhesion <= 0) continue;
        const double dc = reach(R, p) / JkrCurve::kBreak;  // Johnson's d_c
        tn = std::min(tn, std::sqrt(m / (kNeckStiffness * p.normal[sFc] * R / dc)));
      }
    if (tn < s.time) s = {tn, "neck times", "t_neck = sqrt(m*/k_0) of the adhesive neck", 1.0, 0.3, false};
    return s;
  }
  /// dF/dd at zero load (x = 2^(2/3)), in F_c / d_c.
  static constexpr double kNeckStiffness = 0.47622031559045984;  // 0.3 * 2^(2/3)
};

}  // namespace grains::sim
