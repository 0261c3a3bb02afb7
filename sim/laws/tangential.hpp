#pragma once
#include "contact/contact_geometry.hpp"
// Tangential slot.
//  * NoTangential: frictionless; no history, no rotation fields.
//  * SpringTangential: an incremental spring on the accumulated tangential
//    displacement xi (3 doubles of history per contact) with a dashpot,
//    Coulomb limit |F_t| <= mu F_load. Its stiffness and damping are the ones
//    the normal law pairs with it (normal_state.hpp): with Hertz, Mindlin's no-slip
//    spring k_t = 8 G* sqrt(R* d) and eta_t = a sqrt(2/3) sqrt(m* k_t) (the
//    same calibrated ratio as the normal slot), named "mindlin"; with the
//    linear law, k_t = kappa k_n and gamma_t = x gamma_n, named "linear". The
//    history is projected onto the current tangent plane each step and,
//    while sliding, reset so that the spring alone gives the Coulomb force
//    (not spring and dashpot together: where the dashpot alone exceeds the
//    limit, early in a strongly damped contact, that would set the spring
//    against the slip, and friction would later push the slip along;
//    docs/physics.md, Chung & Ooi's test 6).
// Case-file keys: materials[].friction (and the normal law's keys).
#include <cmath>

#include <Eigen/Core>

#include "sim/laws/normal_state.hpp"
#include "sim/laws/pair_params.hpp"

namespace grains::sim {

struct NoTangential {
  static constexpr int history_size = 0;
  static constexpr bool needs_rotation = false;
  static constexpr const char* name = "none";
  template <class Normal>
  static const char* label() { return name; }
  template <class NS>
  static GRAINS_INLINE Eigen::Vector3d force(const Eigen::Vector3d&, const Eigen::Vector3d&, const NS&, double,
                                             const PairParams&, double, double*) {
    return Eigen::Vector3d::Zero();
  }
  static GRAINS_INLINE void rate(const Eigen::Vector3d&, double*) {}
};

struct SpringTangential {
  static constexpr int history_size = 3;
  static constexpr bool needs_rotation = true;
  static constexpr const char* name = "spring";
  /// The name a case file and the pipeline use: the normal law's pairing.
  template <class Normal>
  static const char* label() { return Normal::tangential_name; }
  /// n: unit normal (j -> i); vt: tangential relative velocity of i w.r.t. j at the contact point.
  template <class NS>
  static GRAINS_INLINE Eigen::Vector3d force(const Eigen::Vector3d& n, const Eigen::Vector3d& vt, const NS& ns,
                                             double m, const PairParams& p, double dt, double* h) {
    Eigen::Map<Eigen::Vector3d> xi(h);
    // Project the stored spring onto the current tangent plane. (Its length
    // changes by a factor cos(angle turned in one step): second order in dt.)
    xi -= n * n.dot(xi);
    xi += vt * dt;
    const double kt = ns.tangential_stiffness(p);
    const double eta = ns.tangential_damping(p);
    (void)m;
    Eigen::Vector3d ft = -kt * xi - eta * vt;
    const double limit = p.friction * ns.load;
    const double ft2 = ft.squaredNorm();
    if (ft2 > limit * limit) {
      if (ft2 > 0) {
        ft *= limit / std::sqrt(ft2);
        xi = kt > 0 ? Eigen::Vector3d(-ft / kt) : Eigen::Vector3d::Zero();
      }
    }
    return ft;
  }
  /// d xi/dt = v_t, for integrators that carry the spring in their ODE state
  /// (integrate/arkode.hpp). force() with dt = 0 then gives the force of that
  /// state and projects it (tangent plane, Coulomb limit).
  static GRAINS_INLINE void rate(const Eigen::Vector3d& vt, double* out) {
    Eigen::Map<Eigen::Vector3d> r(out);
    r = vt;
  }
};

}  // namespace grains::sim
