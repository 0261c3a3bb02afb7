#pragma once
// Rigid clumps: the force aggregation and the rigid-body velocity Verlet of
// the bodies in Scene::bodies (the LIGGGHTS multisphere scheme).
//
// Force phase, after every contact stage:
//   F = M g + sum_balls f,   T = sum_balls (x_ball - x_com) x f + tau_ball
// Drift:  v += dt/2 F/M, L += dt/2 T; x += dt v; q by the quaternion midpoint
//         rotation of integrate/rigid_body.hpp (same functions); then every
//         ball is put back on its body: x = x_com + R r, v = v + w x (R r), w.
// Kick:   v += dt/2 F/M, L += dt/2 T; the balls' v and w follow.
// The balls' own integrators skip them (VerletDrift<.., true>); in scenes
// with ellipsoids the rigid-body integrator moves them too, and the body
// stages, which run after it in each phase, overwrite that.
#include <algorithm>
#include <vector>

#include "sim/integrate/rigid_body.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {

/// Sets every clump ball from its body: position (when `positions`),
/// velocity, and the angular velocity / orientation fields when they exist.
inline void place_clump_balls(ParticleStore& p, const BodyStore& b, bool positions) {
  // Reused across calls: this runs twice per step, and must not allocate.
  static thread_local std::vector<Eigen::Matrix3d> R;
  R.resize(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) R[k] = b.orientation[k].toRotationMatrix();
  const bool spin = p.fields().has(Field::AngularVelocity), orient = p.fields().has(Field::Orientation);
  const bool mom = p.fields().has(Field::AngularMomentum);
  const std::size_t n = p.n_owned();
  for (std::size_t i = 0; i < n; ++i) {
    if (p.body[i] < 0) continue;
    const auto k = static_cast<std::size_t>(b.index_of(p.body[i]));
    const Vec3 r = R[k] * p.body_offset[i];
    if (positions) p.x[i] = b.x[k] + r;
    p.v[i] = b.v[k] + b.omega[k].cross(r);
    if (spin) p.omega[i] = b.omega[k];
    if (orient) p.orientation[i] = b.orientation[k];
    if (mom) p.angular_momentum[i].setZero();
  }
}

inline void clump_half_kick(BodyStore& b, double half_dt) {
  for (std::size_t k = 0; k < b.size(); ++k) {
    b.v[k] += (half_dt / b.mass[k]) * b.force[k];
    b.angular_momentum[k] += half_dt * b.torque[k];
    b.omega[k] = angular_velocity(b.orientation[k], b.inertia[k], b.angular_momentum[k]);
  }
}

/// Sums the balls' forces and torques onto their bodies (and gravity).
class ClumpForces final : public Stage {
 public:
  std::string name() const override { return "force.clump_sum(balls -> bodies)"; }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    auto& b = s.bodies;
    const auto& p = s.particles;
    for (std::size_t k = 0; k < b.size(); ++k) {
      b.force[k] = b.mass[k] * s.gravity;
      b.torque[k].setZero();
    }
    const bool tau = p.fields().has(Field::Torque);
    const std::size_t n = p.n_owned();
    auto add = [&](std::size_t i) {
      const auto k = static_cast<std::size_t>(b.index_of(p.body[i]));
      b.force[k] += p.f[i];
      b.torque[k] += (p.x[i] - b.x[k]).cross(p.f[i]);
      if (tau) b.torque[k] += p.torque[i];
    };
    if (!s.deterministic) {
      for (std::size_t i = 0; i < n; ++i)
        if (p.body[i] >= 0) add(i);
      return;
    }
    // Deterministic mode: the balls in global-id order, whatever their local
    // order (which depends on ranks and re-sorting); refreshed at rebuilds.
    if (order_builds_ != s.neighbors.stats().builds || order_.size() > n) {
      order_.clear();
      for (std::size_t i = 0; i < n; ++i)
        if (p.body[i] >= 0) order_.push_back(i);
      std::sort(order_.begin(), order_.end(), [&p](std::size_t a, std::size_t c) { return p.id[a] < p.id[c]; });
      order_builds_ = s.neighbors.stats().builds;
    }
    for (const auto i : order_) add(i);
  }

 private:
  std::vector<std::size_t> order_;
  long order_builds_ = -1;
};

class ClumpDrift final : public Stage {
 public:
  std::string name() const override { return "clump.kick_drift(quaternion midpoint)+place_balls"; }
  Phase phase() const override { return Phase::Drift; }
  void run(Scene& s) override {
    auto& b = s.bodies;
    const double dt = s.clock.dt;
    clump_half_kick(b, 0.5 * dt);
    for (std::size_t k = 0; k < b.size(); ++k) {
      b.x[k] += dt * b.v[k];
      const Vec3& L = b.angular_momentum[k];
      const Vec3 w_mid = half_step_angular_velocity(b.orientation[k].toRotationMatrix(), b.inertia[k].cwiseInverse(), L,
                                                    0.5 * dt);
      b.orientation[k] = rotate(b.orientation[k], w_mid, dt);
      b.omega[k] = angular_velocity(b.orientation[k], b.inertia[k], L);
    }
    place_clump_balls(s.particles, b, true);
  }
};

class ClumpKick final : public Stage {
 public:
  std::string name() const override { return "clump.kick+ball_velocities"; }
  Phase phase() const override { return Phase::Kick; }
  void run(Scene& s) override {
    clump_half_kick(s.bodies, 0.5 * s.clock.dt);
    place_clump_balls(s.particles, s.bodies, false);
  }
};

}  // namespace grains::sim
