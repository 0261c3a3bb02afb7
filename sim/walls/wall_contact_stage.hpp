#pragma once
#include "contact/contact_geometry.hpp"
// Particle-wall contacts of every wall kind through the same Law as particle
// pairs: the wall is body j with infinite mass (m* = m_i), the wall's
// velocity and no spin. One stage for all walls: each kind supplies its
// contacts (wall_kind.hpp), this loop evaluates them over the wall's near
// list, keeps the history per (particle, wall slot) in the particle's
// wall-history field and clears the slots a particle no longer uses. With
// Shapes = true (scenes with ellipsoids) the geometry is chosen per
// particle: sphere or ellipsoid.
#include <algorithm>

#include "sim/laws/contact_law.hpp"
#include "sim/scene/stage.hpp"
#include "sim/state/parallel_for.hpp"

namespace grains::sim {

template <class Law, bool Rotation = Law::needs_rotation>
struct WallContact {
  static GRAINS_INLINE void apply(ParticleStore& p, std::size_t i, const contact::ContactGeometry& g,
                                  const Vec3& wall_velocity, const PairParams& pp, double dt, double* hist) {
    Vec3 v_rel = p.v[i] - wall_velocity;
    Vec3 w_rel = Vec3::Zero();
    Vec3 ci;
    if constexpr (Rotation) {
      ci = g.point - p.x[i];
      v_rel += p.omega[i].cross(ci);
      w_rel = p.omega[i];
    }
    const auto r = Law::evaluate(g, v_rel, w_rel, p.mass[i], pp, dt, hist);
    p.f[i] += r.force;
    if constexpr (Rotation) p.torque[i] += ci.cross(r.force) + r.rolling_torque;
  }
};

template <class Law, bool Shapes = false>
class WallStage final : public Stage {
 public:
  std::string name() const override {
    return std::string("force.walls") + (Shapes ? "[sphere|ellipsoid]" : "") + "<" + Law::name() + ">";
  }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    s.walls.for_each([&](const auto& wall, std::size_t w) { run_wall(s, wall, s.neighbors.wall_near[w]); });
  }

 private:
  template <class K>
  static void run_wall(Scene& s, const K& wall, const std::vector<std::uint32_t>& near) {
    ParticleStore& p = s.particles;
    constexpr int H = Law::history_size;
    const int WH = p.wall_history_size();
    const int slots = wall.history_slots;
    const auto nn = static_cast<std::ptrdiff_t>(near.size());
    // Each particle appears once per wall: rows are independent.
    parallel_for(s.deterministic && use_threads(nn, 256), nn, [&](std::ptrdiff_t m) {
      const std::size_t i = near[static_cast<std::size_t>(m)];
      double* hist = H > 0 ? p.wall_history.data() + i * WH + wall.history_slot * H : nullptr;
      auto held = [&](int k) {
        if constexpr (H > 0) return std::any_of(hist + k * H, hist + (k + 1) * H, [](double v) { return v != 0.0; });
        (void)k;
        return false;
      };
      unsigned used = 0;  // the slots a contact used this step
      wall.template contacts<Shapes>(p, i, held, [&](const contact::ContactGeometry& g, int slot) {
        used |= 1u << slot;
        WallContact<Law, Law::needs_rotation || Shapes>::apply(p, i, g, wall.velocity,
                                                              s.pairs(p.material[i], wall.material), s.clock.dt,
                                                              H > 0 ? hist + slot * H : nullptr);
      });
      if constexpr (H > 0) {
        if (slots == 1) {  // most walls: one fill of known size
          if (used == 0) std::fill_n(hist, H, 0.0);
        } else {
          for (int k = 0; k < slots; ++k)
            if (!(used >> k & 1u)) std::fill_n(hist + k * H, H, 0.0);
        }
      }
    });
  }
};

}  // namespace grains::sim
