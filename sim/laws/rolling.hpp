#pragma once
#include "contact/contact_geometry.hpp"
// Rolling-resistance slot.
//  * NoRolling.
//  * EpsdRolling: elastic-plastic spring-dashpot model (Ai, Chen, Rotter & Ooi,
//    Powder Technol. 206, 2011, model type C without the viscous term): a
//    rolling spring of stiffness k_r = 2.25 S_n mu_r^2 R*^2 on the relative
//    rotation, torque limited to mu_r R* F_n (full mobilisation). The torque
//    is kept as 3 doubles of history, rotated into the tangent plane. S_n
//    and F_n are the normal law's (normal_state.hpp: stiffness, load).
// Case-file key: materials[].rolling_friction.
#include <cmath>

#include <Eigen/Core>

#include "sim/laws/normal_state.hpp"
#include "sim/laws/pair_params.hpp"

namespace grains::sim {

struct NoRolling {
  static constexpr int history_size = 0;
  static constexpr bool needs_rotation = false;
  static constexpr const char* name = "none";
  template <class NS>
  static GRAINS_INLINE Eigen::Vector3d torque(const Eigen::Vector3d&, const Eigen::Vector3d&, const NS&, double,
                                       const PairParams&, double, double*) {
    return Eigen::Vector3d::Zero();
  }
  template <class NS>
  static GRAINS_INLINE void rate(const Eigen::Vector3d&, const Eigen::Vector3d&, const NS&, double,
                                 const PairParams&, double*) {}
};

struct EpsdRolling {
  static constexpr int history_size = 3;
  static constexpr bool needs_rotation = true;
  static constexpr const char* name = "epsd";
  /// w_rel = omega_i - omega_j. Returns the rolling torque on i (j gets minus it).
  template <class NS>
  static GRAINS_INLINE Eigen::Vector3d torque(const Eigen::Vector3d& n, const Eigen::Vector3d& w_rel,
                                       const NS& ns, double R, const PairParams& p, double dt,
                                       double* h) {
    Eigen::Map<Eigen::Vector3d> mr(h);
    const double len2 = mr.squaredNorm();
    if (len2 > 0) {
      mr -= n * n.dot(mr);
      const double l2 = mr.squaredNorm();
      if (l2 > 0) mr *= std::sqrt(len2 / l2);
    }
    const Eigen::Vector3d wr = w_rel - n * n.dot(w_rel);
    mr -= stiffness(ns, R, p) * dt * wr;
    const double limit = p.rolling_friction * R * ns.load;
    const double m2 = mr.squaredNorm();
    if (m2 > limit * limit && m2 > 0) mr *= limit / std::sqrt(m2);
    return mr;
  }
  /// Rolling stiffness k_r = 2.25 S_n mu_r^2 R*^2.
  template <class NS>
  static GRAINS_INLINE double stiffness(const NS& ns, double R, const PairParams& p) {
    return 2.25 * ns.stiffness(p) * p.rolling_friction * p.rolling_friction * R * R;
  }
  /// d m_r/dt = -k_r w_r (w_r: w_rel in the tangent plane), for integrators
  /// that carry the torque in their ODE state (integrate/arkode.hpp);
  /// torque() with dt = 0 then projects it (length kept, limit).
  template <class NS>
  static GRAINS_INLINE void rate(const Eigen::Vector3d& n, const Eigen::Vector3d& w_rel, const NS& ns,
                                 double R, const PairParams& p, double* out) {
    const Eigen::Vector3d wr = w_rel - n * n.dot(w_rel);
    Eigen::Map<Eigen::Vector3d> r(out);
    r = -stiffness(ns, R, p) * wr;
  }
};

}  // namespace grains::sim
