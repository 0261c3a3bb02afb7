#pragma once
// Damping calibrated to the requested coefficient of restitution.
//
// Normal law (see normal_hertz.hpp):
//   F_n = max(0, K d^{3/2} + a sqrt(m* K) d^{1/4} d_dot),   K = 4/3 E* sqrt(R*).
// With d = X u, t = T s, T = (m*/(K sqrt(v)))^{2/5}, X = v T the impact becomes
//   u'' = -max(0, u^{3/2} + a u^{1/4} u'),   u(0) = 0, u'(0) = 1,
// which has no parameter but a: the restitution e = -u'(s_end) depends on a
// alone, for every mass, radius, stiffness and impact speed. We integrate this
// dimensionless ODE once (RK4, fine step) and invert e(a) by bisection, so the
// achieved restitution equals the target for the clamped law (no attractive
// force while unloading). The LIGGGHTS/EDEM formula
// eta_n = -2 sqrt(5/6) beta sqrt(S_n m*) corresponds to a = -2 sqrt(5/6) sqrt(3/2) beta
// = -sqrt(5) beta; it achieves the target only without the clamp and only
// approximately (see tests/physics/contact/test_normal_impact.cpp).
namespace grains::sim {

/// Achieved restitution of the clamped damped Hertz law for dimensionless damping a >= 0.
double restitution_for_damping(double a);
/// The damping a >= 0 that achieves restitution e in (0, 1]; e = 1 gives 0.
/// Throws std::invalid_argument outside (0, 1]. Results are cached.
double damping_for_restitution(double e);
/// The dimensionless damping implied by the LIGGGHTS/EDEM beta formula.
double liggghts_damping(double e);

}  // namespace grains::sim
