#pragma once
// What a normal law hands to the other slots. Each normal law returns its
// own small state type (normal_hertz.hpp: HertzState, normal_linear.hpp:
// LinearState) with the same members; the tangential spring, the rolling
// spring and the Coulomb and rolling limits read only these, so they work
// with every registered normal law (sim/laws/normal_laws.hpp). The derived
// quantities are member functions, evaluated where a slot needs them (a
// frictionless scene never computes a tangential stiffness):
//   force      normal force magnitude on body i along +n (repulsive > 0);
//              laws that clamp it (Hertz) never make it negative, an
//              unclamped linear spring-dashpot pulls briefly at the end of a
//              damped contact, as LAMMPS's and LIGGGHTS's hooke do
//   load       the load the Coulomb and rolling limits scale with (>= 0)
//   stiffness(p)
//              tangent normal stiffness S_n = dF_n/d(overlap) of the elastic
//              part, N/m (the rolling spring scales with it)
//   damping(p)
//              the normal dashpot dF_n/d(overlap rate), N s/m (a servo wall's
//              gain, sim/walls/wall_control.hpp)
//   tangential_stiffness(p), tangential_damping(p)
//              the tangential spring (N/m) and dashpot (N s/m) this normal law
//              pairs with: Hertz gives Mindlin's k_t = 8 G* sqrt(R* d) and the
//              dashpot that damps it as the normal one is damped; the linear
//              law gives k_t = kappa k_n and gamma_t = x gamma_n (LAMMPS
//              gran/hooke/history, LIGGGHTS hooke)
// (p: the pair's PairParams.)
#include "contact/contact_geometry.hpp"
#include "sim/laws/pair_params.hpp"
