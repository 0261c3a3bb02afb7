#pragma once
// Force-phase stages that do not involve contacts.
#include "sim/scene/stage.hpp"

namespace grains::sim {

/// Starts the force accumulation: F = 0, or F = m g when the scene has
/// gravity (one pass instead of two), and T = 0 when the scene rotates.
/// In scenes with clumps (Clumps = true) the balls of a clump start at
/// F = 0: their mass field holds the body's mass (for m* of contacts), and
/// gravity acts on the body (BodyForces), not on its balls.
template <bool Rotation, bool WithGravity = false, bool Clumps = false>
class ClearForces final : public Stage {
 public:
  std::string name() const override {
    return std::string("force.clear") + (Rotation ? "+torque" : "") + (WithGravity ? "+gravity" : "") +
           (Clumps ? "(clump balls: 0)" : "");
  }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    auto& p = s.particles;
    if constexpr (WithGravity) {
      const Vec3 g = s.gravity;
      const std::size_t n = p.n_owned();
      if constexpr (Clumps) {
        for (std::size_t i = 0; i < n; ++i) p.f[i] = p.body[i] >= 0 ? Vec3::Zero() : Vec3(p.mass[i] * g);
      } else {
        for (std::size_t i = 0; i < n; ++i) p.f[i] = p.mass[i] * g;
      }
      for (std::size_t i = n; i < p.size(); ++i) p.f[i].setZero();
    } else {
      for (auto& f : p.f) f.setZero();
    }
    if constexpr (Rotation)
      for (auto& t : p.torque) t.setZero();
  }
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
