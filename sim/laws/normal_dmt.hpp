#pragma once
// Normal slot: DMT adhesion (Derjaguin, Muller & Toporov, J. Colloid
// Interface Sci. 53, 1975), the stiff-grain limit of adhesive elastic
// contact: the Hertz force of normal_hertz.hpp (damped, clamped at zero)
// less a constant attraction, the Bradley / DMT pull-off force,
//   F_n = max(0, K d^{3/2} + a sqrt(m* K) d^{1/4} d_dot) - F_c,
//   K = 4/3 E* sqrt(R*),   F_c = 2 pi w R*,
// while the grains overlap (d > 0): the contact forms on touching and ends
// at d = 0, where the attraction drops to zero (as DMT and LAMMPS's dmt
// model have it; the contact radius is Hertz's sqrt(R* d)). w is the work of
// adhesion of the material pair (J/m^2): by default 2 sqrt(g_a g_b) from the
// materials' surface_energy g (w = 2 g for two surfaces of one material),
// or contact.pairs[].work_of_adhesion. The damping is the Hertz part's, with
// the calibration that gives the pair's restitution when w = 0 (LIGGGHTS
// damps its cohesive contacts the same way, from the repulsive part only);
// with w > 0 slow grains lose more and stick. The Coulomb and rolling limits
// scale with the load F_n + 2 F_c (= Hertz part + F_c: the cohesive limit of
// Marshall, J. Comput. Phys. 228, 2009, eq. 43, which LAMMPS's granular
// models use), so that an adhesive contact resists sliding at
// zero and at small tensile loads. Mindlin's tangential spring 8 G* sqrt(R* d)
// as with Hertz. With w = 0 it is the Hertz law exactly.
// Registered in normal_laws.hpp.
#include <cmath>
#include <string>
#include <vector>

#include "sim/laws/normal_hertz.hpp"

namespace grains::sim {

struct DmtNormal {
  static constexpr const char* name = "dmt";
  static constexpr const char* tangential_name = "mindlin";
  /// The law acts on the pairs' work of adhesion (materials' surface_energy).
  static constexpr bool adhesive = true;
  enum Slot { sTwoPiW };  // PairParams::normal: 2 pi w

  static std::string summary() {
    return "DMT adhesion (Derjaguin-Muller-Toporov 1975), the stiff-grain limit: the Hertz force (damped as "
           "model: hertz, so the restitution is exact without adhesion) less the pull-off force 2 pi w R* while "
           "the grains overlap, w the pair's work of adhesion: 2 sqrt(g_a g_b) from materials[].surface_energy, "
           "or contact.pairs[].work_of_adhesion. The contact ends at zero overlap. The friction and rolling limits "
           "scale with F_n + 2 F_c (Marshall 2009). Pairs with Mindlin's tangential spring.";
  }
  static std::vector<KeySpec> keys() { return {}; }
  static std::string check(const LawValues&) { return {}; }
  static std::vector<LawValues> examples() { return {LawValues{}}; }

  static std::string prepare(PairParams& p, const LawValues& v) {
    if (auto e = HertzNormal::prepare(p, v); !e.empty()) return e;
    p.normal[sTwoPiW] = 2.0 * M_PI * p.work_of_adhesion;
    return {};
  }

  /// The Hertz state with the attraction: force = Hertz - F_c, load = Hertz + F_c.
  static GRAINS_INLINE HertzState evaluate(double d, double d_dot, double R, double m, const PairParams& p) {
    HertzState s = HertzNormal::evaluate(d, d_dot, R, m, p);
    const double fc = p.normal[sTwoPiW] * R;
    s.load = s.force + fc;
    s.force -= fc;
    return s;
  }

  static StepScale step_scale(const PairTable& t, const GrainExtremes& g) { return HertzNormal::step_scale(t, g); }
};

}  // namespace grains::sim
