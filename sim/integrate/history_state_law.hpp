#pragma once
// A contact law whose history is part of the integrator's ODE state
// (integrate/arkode.hpp). The per-contact history buffer holds, for the
// wrapped law's H doubles, [state (H) | rate (H)]: the integrator writes the
// state of its trial point, the law computes the force of that state
// (ContactLaw::evaluate_rate: evaluate() with dt = 0, which also projects the
// state onto the tangent plane and the Coulomb and rolling limits, in place)
// and writes d(state)/dt. The time step passed by the stages is ignored: the
// integrator, not the law, advances the history.
#include <string>

#include "sim/laws/contact_law.hpp"

namespace grains::sim {

template <class Law>
struct HistoryInState {
  using N = typename Law::N;
  using T = typename Law::T;
  using R = typename Law::R;
  using C = typename Law::C;
  using Result = typename Law::Result;
  static constexpr int state_size = Law::history_size;
  static constexpr int history_size = 2 * Law::history_size;
  static constexpr bool needs_rotation = Law::needs_rotation;

  static std::string name() { return Law::name() + "+history:ode_state"; }

  static GRAINS_INLINE Result evaluate(const contact::ContactGeometry& g, const Eigen::Vector3d& v_rel,
                                       const Eigen::Vector3d& w_rel, double m, const PairParams& p, double /*dt*/,
                                       double* hist) {
    return Law::evaluate_rate(g, v_rel, w_rel, m, p, hist, hist + state_size);
  }
};

}  // namespace grains::sim
