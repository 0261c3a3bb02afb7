#pragma once
// What a normal law hands to the other slots: the tangential spring, the
// rolling spring and the Coulomb and rolling limits read this struct only,
// so they work with every registered normal law (sim/laws/normal_laws.hpp).
#include "contact/contact_geometry.hpp"

namespace grains::sim {

struct NormalState {
  /// Normal force magnitude on body i along +n (repulsive > 0). Laws that
  /// clamp it (Hertz) never make it negative; an unclamped linear
  /// spring-dashpot pulls briefly at the end of a damped contact, as in
  /// LAMMPS's and LIGGGHTS's hooke.
  double force;
  /// The load the Coulomb and rolling limits scale with (>= 0).
  double load;
  /// Tangent normal stiffness S_n = dF_n/d(overlap) of the elastic part, N/m
  /// (the rolling spring scales with it).
  double stiffness;
  /// The tangential spring and dashpot this normal law pairs with: Hertz
  /// gives Mindlin's k_t = 8 G* sqrt(R* d) and the dashpot that damps it as
  /// the normal one is damped; the linear law gives k_t = kappa k_n and
  /// gamma_t = x gamma_n (LAMMPS gran/hooke/history, LIGGGHTS hooke).
  double tangential_stiffness;  // N/m
  double tangential_damping;    // N s/m
};

}  // namespace grains::sim
