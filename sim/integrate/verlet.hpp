#pragma once
// Velocity Verlet, split in two stages around the force phase:
//   drift:  v += dt/2 F/m;  x += dt v          (and w += dt/2 T/I when rotating)
//   kick:   v += dt/2 F/m                      (and w += dt/2 T/I)
// Rotation is a template parameter: a scene without rotational degrees of
// freedom instantiates the translational version only. Spheres have an
// isotropic inertia, so w integrates directly in the world frame; bodies
// with orientation use the quaternion integrator (integrate/rotation.hpp).
//
// Between two steps whose state nobody reads (no frame, check or checkpoint
// at that step: Pipeline::step with may_wait), the kick waits and the next
// drift does both half kicks in one pass over v, w, F, T, 1/m and I: the
// same additions in the same order, so the same bits, with the kick's
// stream of every grain's fields saved (the integration passes are bound by
// memory traffic, bench/RESULTS.md).
#include <memory>
#include <string>

#include "sim/scene/body_forces.hpp"
#include "sim/scene/stage.hpp"
#include "sim/state/parallel_for.hpp"

namespace grains::sim {

// The loops read the fields through pointers taken before them and the steps
// as copies: Eigen's packet stores may alias anything, so a field reached
// through the store (p.v[i]) or a step held by reference would be loaded
// again at every particle.

// SkipClumpBalls (scenes with clumps only): balls of a clump are moved by
// their body (integrate/clump_bodies.hpp), not here.
template <bool Rotation, bool SkipClumpBalls = false>
inline void verlet_half_kick(ParticleStore& p, const double half_dt) {
  const auto n = static_cast<std::ptrdiff_t>(p.n_owned());
  const std::int64_t* body = SkipClumpBalls ? p.body.data() : nullptr;
  {
    Vec3* v = p.v.data();
    const Vec3* f = p.f.data();
    const double* im = p.inv_mass.data();
    parallel_for(use_threads(n), n, [=](std::ptrdiff_t i) {
      if constexpr (SkipClumpBalls)
        if (body[i] >= 0) return;
      v[i] += (half_dt * im[i]) * f[i];
    });
  }
  if constexpr (Rotation) {
    Vec3* w = p.omega.data();
    const Vec3* t = p.torque.data();
    const Vec3* in = p.inertia.data();
    parallel_for(use_threads(n), n, [=](std::ptrdiff_t i) {
      if constexpr (SkipClumpBalls)
        if (body[i] >= 0) return;
      w[i] += (half_dt / in[i].x()) * t[i];
    });
  }
}

// The drift of the particles that are not clump balls in one pass: the half
// kick (Two: both, v += h1 F/m then v += h2 F/m, each as verlet_half_kick
// adds it; with equal steps the one quotient h/I serves both),
// x += dt v, and with Start the start of the force phase, F = m g (Gravity)
// or 0 and T = 0 (ForceStart), each particle's fields read once. The same
// operations per particle as the separate passes (the same bits); one
// stream of x, v, w, F, T, 1/m, I and m instead of three (and the clear's
// fourth).
template <bool Rotation, bool Two, bool Start, bool Gravity>
inline void verlet_kick_drift(ParticleStore& p, const double h1, const double h2, const double dt, const Vec3 g) {
  const auto n = static_cast<std::ptrdiff_t>(p.n_owned());
  Vec3* const x = p.x.data();
  Vec3* const v = p.v.data();
  Vec3* const f = p.f.data();
  const double* const im = p.inv_mass.data();
  const double* const m = p.mass.data();
  Vec3* const w = Rotation ? p.omega.data() : nullptr;
  Vec3* const t = Rotation ? p.torque.data() : nullptr;
  const Vec3* const in = Rotation ? p.inertia.data() : nullptr;
  const bool equal = h1 == h2;
  parallel_for(use_threads(n), n, [=](std::ptrdiff_t i) {
    if constexpr (Two) {
      const double c1 = h1 * im[i], c2 = h2 * im[i];
      v[i] = (v[i] + c1 * f[i]) + c2 * f[i];
    } else {
      v[i] += (h1 * im[i]) * f[i];
    }
    if constexpr (Rotation) {
      if constexpr (Two) {
        const double c1 = h1 / in[i].x(), c2 = equal ? c1 : h2 / in[i].x();
        w[i] = (w[i] + c1 * t[i]) + c2 * t[i];
      } else {
        w[i] += (h1 / in[i].x()) * t[i];
      }
    }
    x[i] += dt * v[i];
    if constexpr (Start) {
      if constexpr (Gravity)
        f[i] = m[i] * g;
      else
        f[i].setZero();
      if constexpr (Rotation) t[i].setZero();
    }
  });
}

/// The kick that waits for the next drift: shared by the two stages.
struct WaitingKick {
  bool waiting = false;
  double half_dt = 0;  // the kick's own dt / 2
};

template <bool Rotation, bool SkipClumpBalls = false>
class VerletDrift final : public Stage {
 public:
  // `w` is shared with the kick stage of the same pipeline; the drift is the
  // drift phase's first stage, so nothing reads the state before it settles.
  // `start`: shared with ClearForces when this drift starts the owned
  // particles' forces (ForceStart; not with clump balls), else null.
  explicit VerletDrift(std::shared_ptr<WaitingKick> w, std::shared_ptr<ForceStart> start = nullptr)
      : w_(std::move(w)), start_(std::move(start)) {}
  std::string name() const override {
    return std::string(Rotation ? "verlet.kick_drift+rotation" : "verlet.kick_drift") +
           (SkipClumpBalls ? "(free particles)" : "") + (start_ ? "+force_start" : "");
  }
  Phase phase() const override { return Phase::Drift; }
  void run(Scene& s) override {
    ParticleStore& p = s.particles;
    const double dt = s.clock.dt;
    if constexpr (!SkipClumpBalls) {
      const bool two = w_->waiting;
      w_->waiting = false;
      const double h1 = two ? w_->half_dt : 0.5 * dt, h2 = 0.5 * dt;
      auto pass = [&]<bool Two>() {
        if (!start_)
          verlet_kick_drift<Rotation, Two, false, false>(p, h1, h2, dt, s.gravity);
        else if (start_->gravity)
          verlet_kick_drift<Rotation, Two, true, true>(p, h1, h2, dt, s.gravity);
        else
          verlet_kick_drift<Rotation, Two, true, false>(p, h1, h2, dt, s.gravity);
      };
      if (two)
        pass.template operator()<true>();
      else
        pass.template operator()<false>();
      if (start_) start_->done = true;
      return;
    }
    // Clump balls' drift: their kick never waits (VerletKick::can_wait).
    verlet_half_kick<Rotation, SkipClumpBalls>(p, 0.5 * dt);
    const auto n = static_cast<std::ptrdiff_t>(p.n_owned());
    Vec3* x = p.x.data();
    const Vec3* v = p.v.data();
    const std::int64_t* body = SkipClumpBalls ? p.body.data() : nullptr;
    parallel_for(use_threads(n), n, [=](std::ptrdiff_t i) {
      if constexpr (SkipClumpBalls)
        if (body[i] >= 0) return;
      x[i] += dt * v[i];
    });
  }

 private:
  std::shared_ptr<WaitingKick> w_;
  std::shared_ptr<ForceStart> start_;
};

template <bool Rotation, bool SkipClumpBalls = false>
class VerletKick final : public Stage {
 public:
  explicit VerletKick(std::shared_ptr<WaitingKick> w) : w_(std::move(w)) {}
  std::string name() const override {
    return std::string(Rotation ? "verlet.kick+rotation" : "verlet.kick") + (SkipClumpBalls ? "(free particles)" : "");
  }
  Phase phase() const override { return Phase::Kick; }
  void run(Scene& s) override { verlet_half_kick<Rotation, SkipClumpBalls>(s.particles, 0.5 * s.clock.dt); }
  // Clump balls' kick shares its phase with the bodies' (never alone).
  bool can_wait() const override { return !SkipClumpBalls; }
  void wait(Scene& s) override {
    w_->waiting = true;
    w_->half_dt = 0.5 * s.clock.dt;
  }
  void settle(Scene& s) override {
    if (!w_->waiting) return;
    w_->waiting = false;
    verlet_half_kick<Rotation, SkipClumpBalls>(s.particles, w_->half_dt);
  }

 private:
  std::shared_ptr<WaitingKick> w_;
};

/// Moves walls with their prescribed velocities (only when some wall moves).
class MoveWalls final : public Stage {
 public:
  std::string name() const override { return "walls.move"; }
  Phase phase() const override { return Phase::Drift; }
  void run(Scene& s) override { s.walls.advance(s.clock.dt); }
};

}  // namespace grains::sim
