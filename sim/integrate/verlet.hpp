#pragma once
// Velocity Verlet, split in two stages around the force phase:
//   drift:  v += dt/2 F/m;  x += dt v          (and w += dt/2 T/I when rotating)
//   kick:   v += dt/2 F/m                      (and w += dt/2 T/I)
// Rotation is a template parameter: a scene without rotational degrees of
// freedom instantiates the translational version only. Spheres have an
// isotropic inertia, so w integrates directly in the world frame; bodies
// with orientation use the quaternion integrator (integrate/rotation.hpp).
#include <string>

#include "sim/scene/stage.hpp"
#include "sim/state/parallel_for.hpp"

namespace grains::sim {

// SkipClumpBalls (scenes with clumps only): balls of a clump are moved by
// their body (integrate/clump_bodies.hpp), not here.
template <bool Rotation, bool SkipClumpBalls = false>
inline void verlet_half_kick(ParticleStore& p, double half_dt) {
  const auto n = static_cast<std::ptrdiff_t>(p.n_owned());
  parallel_for(use_threads(n), n, [&](std::ptrdiff_t i) {
    if constexpr (SkipClumpBalls)
      if (p.body[i] >= 0) return;
    p.v[i] += (half_dt * p.inv_mass[i]) * p.f[i];
  });
  if constexpr (Rotation)
    parallel_for(use_threads(n), n, [&](std::ptrdiff_t i) {
      if constexpr (SkipClumpBalls)
        if (p.body[i] >= 0) return;
      p.omega[i] += (half_dt / p.inertia[i].x()) * p.torque[i];
    });
}

template <bool Rotation, bool SkipClumpBalls = false>
class VerletDrift final : public Stage {
 public:
  std::string name() const override {
    return std::string(Rotation ? "verlet.kick_drift+rotation" : "verlet.kick_drift") +
           (SkipClumpBalls ? "(free particles)" : "");
  }
  Phase phase() const override { return Phase::Drift; }
  void run(Scene& s) override {
    ParticleStore& p = s.particles;
    const double dt = s.clock.dt;
    verlet_half_kick<Rotation, SkipClumpBalls>(p, 0.5 * dt);
    const auto n = static_cast<std::ptrdiff_t>(p.n_owned());
    parallel_for(use_threads(n), n, [&](std::ptrdiff_t i) {
      if constexpr (SkipClumpBalls)
        if (p.body[i] >= 0) return;
      p.x[i] += dt * p.v[i];
    });
  }
};

template <bool Rotation, bool SkipClumpBalls = false>
class VerletKick final : public Stage {
 public:
  std::string name() const override {
    return std::string(Rotation ? "verlet.kick+rotation" : "verlet.kick") + (SkipClumpBalls ? "(free particles)" : "");
  }
  Phase phase() const override { return Phase::Kick; }
  void run(Scene& s) override { verlet_half_kick<Rotation, SkipClumpBalls>(s.particles, 0.5 * s.clock.dt); }
};

/// Moves walls with their prescribed velocities (only when some wall moves).
class MoveWalls final : public Stage {
 public:
  std::string name() const override { return "walls.move"; }
  Phase phase() const override { return Phase::Drift; }
  void run(Scene& s) override { s.walls.advance(s.clock.dt); }
};

}  // namespace grains::sim
