#pragma once
// A contact law composed of slots (normal, tangential, rolling, cohesion),
// each a small struct with static traits. The composition knows nothing
// about shapes: it consumes a contact::ContactGeometry and the relative
// motion at the contact point. An absent slot is an empty struct, so its
// code and its history vanish at compile time (no run-time "enabled" flags).
// The normal law hands the other slots a law-neutral normal state
// (normal_state.hpp). The registries of each slot are below and in
// normal_laws.hpp.
#include <algorithm>
#include <string>

#include <Eigen/Core>

#include "contact/contact_geometry.hpp"
#include "sim/laws/cohesion.hpp"
#include "sim/laws/normal_laws.hpp"
#include "sim/registry.hpp"
#include "sim/laws/rolling.hpp"
#include "sim/laws/tangential.hpp"

namespace grains::sim {

/// The other slots' registries; the first entry of each is "absent".
using TangentialLaws = TypeList<NoTangential, SpringTangential>;
using RollingLaws = TypeList<NoRolling, EpsdRolling>;
using CohesionLaws = TypeList<NoCohesion, SjkrCohesion>;

template <class Normal, class Tangential, class Rolling, class Cohesion>
struct ContactLaw {
  using N = Normal;
  using T = Tangential;
  using R = Rolling;
  using C = Cohesion;
  static constexpr int tangential_history = T::history_size;
  /// The normal law's contact state (JKR: in contact or not) comes after the springs'.
  static constexpr int normal_history = sim::normal_history<N>();
  static constexpr int history_size = T::history_size + R::history_size + normal_history;
  static constexpr bool needs_rotation = T::needs_rotation || R::needs_rotation;

  static std::string name() {
    return std::string(N::name) + "+tangential:" + T::template label<N>() + "+rolling:" + R::name +
           "+cohesion:" + C::name;
  }

  /// The normal law's state of the contact (with its own contact state, if it keeps one).
  static GRAINS_INLINE auto normal_state(const contact::ContactGeometry& g, double d_dot, double m, const PairParams& p,
                                         double* hist) {
    if constexpr (normal_history > 0)
      return N::evaluate(g.overlap, d_dot, g.radius, m, p, hist[T::history_size + R::history_size]);
    else
      return N::evaluate(g.overlap, d_dot, g.radius, m, p);
  }

  struct Result {
    Eigen::Vector3d force;         // on body i; body j receives -force
    Eigen::Vector3d rolling_torque;  // on body i; body j receives minus it
    double stiffness;                // the normal law's tangent stiffness dF/d(overlap) (a servo wall's gain)
    double damping;                  // and its dashpot dF/d(overlap rate)
  };

  /// v_rel: velocity of i relative to j at the contact point; w_rel = omega_i - omega_j
  /// (ignored without rotation). m: effective mass. hist: history_size doubles.
  static GRAINS_INLINE Result evaluate(const contact::ContactGeometry& g, const Eigen::Vector3d& v_rel,
                                const Eigen::Vector3d& w_rel, double m, const PairParams& p, double dt,
                                double* hist) {
    Result out;
    if constexpr (normal_history > 0) {  // a contact that may outlive touching
      if (!N::engaged(g.overlap, g.radius, p, hist[T::history_size + R::history_size])) {
        std::fill_n(hist, history_size, 0.0);
        out.force.setZero();
        out.rolling_torque.setZero();
        out.stiffness = 0;
        out.damping = 0;
        return out;
      }
    }
    const Eigen::Vector3d& n = g.normal;
    const double vn = v_rel.dot(n);
    const auto ns = normal_state(g, -vn, m, p, hist);
    out.force = n * (ns.force - C::force(g.overlap, g.radius, p));
    out.stiffness = ns.stiffness(p);
    out.damping = ns.damping(p);
    if constexpr (T::history_size > 0) {
      const Eigen::Vector3d vt = v_rel - n * vn;
      out.force += T::force(n, vt, ns, m, p, dt, hist);
    }
    if constexpr (R::history_size > 0) {
      out.rolling_torque = R::torque(n, w_rel, ns, g.radius, p, dt, hist + T::history_size);
    } else {
      out.rolling_torque.setZero();
    }
    (void)w_rel;
    (void)dt;
    (void)hist;
    return out;
  }

  /// For integrators that carry the history in their ODE state
  /// (integrate/arkode.hpp): the force of the history state `hist`, which is
  /// projected in place as evaluate() does with dt = 0 (tangent plane,
  /// Coulomb and rolling limits), and d(hist)/dt into `rate` (history_size
  /// doubles): the tangential relative velocity for the spring, -k_r w_r for
  /// the rolling torque.
  static GRAINS_INLINE Result evaluate_rate(const contact::ContactGeometry& g, const Eigen::Vector3d& v_rel,
                                     const Eigen::Vector3d& w_rel, double m, const PairParams& p, double* hist,
                                     double* rate) {
    const Result out = evaluate(g, v_rel, w_rel, m, p, 0.0, hist);
    if constexpr (history_size > 0) {
      const Eigen::Vector3d& n = g.normal;
      const double vn = v_rel.dot(n);
      if constexpr (T::history_size > 0) T::rate(v_rel - n * vn, rate);
      if constexpr (R::history_size > 0) {
        const auto ns = normal_state(g, -vn, m, p, hist);
        R::rate(n, w_rel, ns, g.radius, p, rate + T::history_size);
      }
      if constexpr (normal_history > 0) std::fill_n(rate + T::history_size + R::history_size, normal_history, 0.0);
    }
    (void)rate;
    return out;
  }
};

/// Whether a law's contacts may hold beyond touching (JKR, normal_laws.hpp):
/// the stages then look for them within NeighborList::reach().
template <class Law>
constexpr bool holds_beyond_touching() {
  if constexpr (requires { Law::normal_history; })
    return Law::normal_history > 0;
  else
    return false;
}

}  // namespace grains::sim
