#pragma once
// Force-phase stages that do not involve contacts.
#include "sim/scene/stage.hpp"

namespace grains::sim {

/// Zeroes forces (and torques when the scene rotates) before accumulation.
template <bool Rotation>
class ClearForces final : public Stage {
 public:
  std::string name() const override { return Rotation ? "force.clear+torque" : "force.clear"; }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    auto& p = s.particles;
    for (auto& f : p.f) f.setZero();
    if constexpr (Rotation)
      for (auto& t : p.torque) t.setZero();
  }
};

/// Uniform gravity, F = m g. Case-file key: `gravity: [gx, gy, gz]` (m/s^2).
class Gravity final : public Stage {
 public:
  std::string name() const override { return "force.gravity"; }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    auto& p = s.particles;
    const Vec3 g = s.gravity;
    const std::size_t n = p.n_owned();
    for (std::size_t i = 0; i < n; ++i) p.f[i] += p.mass[i] * g;
  }
};

}  // namespace grains::sim
