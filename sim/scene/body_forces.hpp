#pragma once
// Force-phase stages that do not involve contacts.
#include "sim/scene/stage.hpp"

namespace grains::sim {

/// Starts the force accumulation: F = 0, or F = m g when the scene has
/// gravity (one pass instead of two), and T = 0 when the scene rotates.
template <bool Rotation, bool WithGravity = false>
class ClearForces final : public Stage {
 public:
  std::string name() const override {
    return std::string("force.clear") + (Rotation ? "+torque" : "") + (WithGravity ? "+gravity" : "");
  }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    auto& p = s.particles;
    if constexpr (WithGravity) {
      const Vec3 g = s.gravity;
      const std::size_t n = p.n_owned();
      for (std::size_t i = 0; i < n; ++i) p.f[i] = p.mass[i] * g;
      for (std::size_t i = n; i < p.size(); ++i) p.f[i].setZero();
    } else {
      for (auto& f : p.f) f.setZero();
    }
    if constexpr (Rotation)
      for (auto& t : p.torque) t.setZero();
  }
};

}  // namespace grains::sim
