#pragma once
// Parameters of one material pair, mixed once at set-up (sim/laws/material.cpp)
// so that the per-contact kernels read a single small struct.
#include <array>

namespace grains::sim {

struct PairParams {
  double E_eff = 0;             // effective Young's modulus E* = 1/((1-v1^2)/E1 + (1-v2^2)/E2), Pa
  double G_eff = 0;             // effective shear modulus G* = 1/((2-v1)/G1 + (2-v2)/G2), Pa
  double damping = 0;           // dimensionless damping a, calibrated from restitution (restitution.hpp)
  double restitution = 1;       // target normal restitution coefficient
  double friction = 0;          // sliding friction coefficient mu
  double rolling_friction = 0;  // rolling friction coefficient mu_r (dimensionless)
  double cohesion = 0;          // cohesion energy density k_c, J/m^3 (SJKR)
  double work_of_adhesion = 0;  // w, J/m^2: 2 sqrt(g_a g_b) of the surface energies (adhesive normal laws)
  double tangential_damping_ratio = 0;  // 2 sqrt(G*/E*): eta_t / (a sqrt(m* K) d^{1/4})
  /// Constants the normal law prepared for this pair, laid out by the law
  /// (its prepare() and evaluate(); e.g. normal_linear.hpp).
  std::array<double, 10> normal{};
};

}  // namespace grains::sim
