#pragma once
// Particle-particle contacts of spheres: geometry from contact/sphere.hpp,
// force from the composed Law. One instantiation per law composition; the
// kernel has no branches for absent effects.
#include <algorithm>

#include "contact/sphere.hpp"
#include "sim/laws/contact_law.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {

template <class Law>
class PairContactStage final : public Stage {
 public:
  std::string name() const override { return "force.pair_contacts<" + Law::name() + ">"; }
  Phase phase() const override { return Phase::Force; }

  void run(Scene& s) override {
    ParticleStore& p = s.particles;
    NeighborList& nl = s.neighbors;
    constexpr int H = Law::history_size;
    const double dt = s.clock.dt;
    const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
    for (std::size_t i = 0; i < rows; ++i) {
      const Vec3 xi = p.x[i];
      const double ri = p.radius[i];
      for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        const std::size_t j = nl.partner[k];
        // Cheap rejection first: most list entries are within the skin but not
        // touching; their history is not even read unless the pair just separated.
        auto& pc = nl.pair_constants[k];
        const Vec3 d = xi - p.x[j];
        const double d2 = d.squaredNorm();
        if (d2 >= pc.contact2) {
          if constexpr (H > 0)
            if (pc.may_touch) std::fill_n(nl.history.data() + static_cast<std::size_t>(k) * H, H, 0.0);
          pc.may_touch = false;
          continue;
        }
        pc.may_touch = true;
        double* hist = H > 0 ? nl.history.data() + static_cast<std::size_t>(k) * H : nullptr;
        // Sphere-sphere geometry (as contact::sphere_sphere, with R* and m*
        // from the list). The contact point lies on the line of centres, so
        // the lever arms are -li n and +lj n: one cross product each for the
        // relative velocity and the torques.
        contact::ContactGeometry g;
        const double dist = std::sqrt(d2);
        g.normal = dist > 0 ? Vec3(d * (1.0 / dist)) : Vec3(0, 0, 1);
        g.overlap = ri + p.radius[j] - dist;
        g.radius = pc.radius;
        const double m = pc.mass;
        const PairParams& pp = s.pairs(p.material[i], p.material[j]);
        const double li = ri - 0.5 * g.overlap, lj = p.radius[j] - 0.5 * g.overlap;
        Vec3 v_rel = p.v[i] - p.v[j];
        Vec3 w_rel = Vec3::Zero();
        if constexpr (Law::needs_rotation) {
          v_rel -= (li * p.omega[i] + lj * p.omega[j]).cross(g.normal);
          w_rel = p.omega[i] - p.omega[j];
        }
        const auto r = Law::evaluate(g, v_rel, w_rel, m, pp, dt, hist);
        p.f[i] += r.force;
        p.f[j] -= r.force;
        if constexpr (Law::needs_rotation) {
          const Vec3 nxf = g.normal.cross(r.force);
          p.torque[i] += r.rolling_torque - li * nxf;
          p.torque[j] -= r.rolling_torque + lj * nxf;
        }
      }
    }
  }
};

}  // namespace grains::sim
