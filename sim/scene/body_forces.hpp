#pragma once
// Force-phase stages that do not involve contacts.
#include <memory>

#include "sim/scene/stage.hpp"

namespace grains::sim {

/// The start of the force phase taken over by the Verlet drift: in its one
/// pass over the owned particles, once it has read F and T for the kick, it
/// writes F = m g (or 0) and T = 0 (sim/integrate/verlet.hpp), and
/// ClearForces then clears only the ghosts. That saves the clear's own pass
/// over F, T and m, bound by memory traffic in large beds (bench/RESULTS.md,
/// 2026-12-02: issue 26). Only where nothing between the drift and the force
/// phase changes a particle's mass or force (assemble_pipeline: no clumps, no
/// radius growth); migrating grains carry their F with them. `done`: the
/// drift did it this step (the clear does it all otherwise: a force phase
/// run without a drift before it).
struct ForceStart {
  bool gravity = false;  // F = m g (ClearForces<.., true>), else F = 0
  bool done = false;
};

/// Starts the force accumulation: F = 0, or F = m g when the scene has
/// gravity (one pass instead of two), and T = 0 when the scene rotates.
/// In scenes with clumps (Clumps = true) the balls of a clump start at
/// F = 0: their mass field holds the body's mass (for m* of contacts), and
/// gravity acts on the body (BodyForces), not on its balls.
template <bool Rotation, bool WithGravity = false, bool Clumps = false>
class ClearForces final : public Stage {
 public:
  /// `start`: shared with the drift that starts the owned particles' forces
  /// (ForceStart), or null.
  explicit ClearForces(std::shared_ptr<ForceStart> start = nullptr) : start_(std::move(start)) {}
  std::string name() const override {
    return std::string("force.clear") + (Rotation ? "+torque" : "") + (WithGravity ? "+gravity" : "") +
           (Clumps ? "(clump balls: 0)" : "") + (start_ ? "(owned: in the drift)" : "");
  }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    auto& p = s.particles;
    const std::size_t n = p.n_owned();
    std::size_t from = 0;  // the first particle to clear
    if (start_ && start_->done) {
      start_->done = false;
      from = n;
    }
    if constexpr (WithGravity) {
      const Vec3 g = s.gravity;
      if constexpr (Clumps) {
        for (std::size_t i = from; i < n; ++i) p.f[i] = p.body[i] >= 0 ? Vec3::Zero() : Vec3(p.mass[i] * g);
      } else {
        for (std::size_t i = from; i < n; ++i) p.f[i] = p.mass[i] * g;
      }
      for (std::size_t i = n; i < p.size(); ++i) p.f[i].setZero();  // the ghosts
    } else {
      for (std::size_t i = from; i < p.size(); ++i) p.f[i].setZero();
    }
    if constexpr (Rotation)
      for (std::size_t i = from; i < p.size(); ++i) p.torque[i].setZero();
  }

 private:
  std::shared_ptr<ForceStart> start_;
};

/// Frozen grains (inv_mass 0: particles[].frozen) take no spin: their torque
/// is cleared after every force (their velocity already stays, F/m being 0
/// for them). Only in scenes with frozen grains that rotate; the force on
/// them is kept (it is what they bear: output's force field).
class FrozenHold final : public Stage {
 public:
  std::string name() const override { return "force.frozen(no torque)"; }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    auto& p = s.particles;
    const std::size_t n = p.n_owned();
    for (std::size_t i = 0; i < n; ++i)
      if (p.inv_mass[i] == 0) p.torque[i].setZero();
  }
};

}  // namespace grains::sim
