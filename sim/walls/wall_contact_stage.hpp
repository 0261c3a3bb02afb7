#pragma once
#include "contact/contact_geometry.hpp"
// Sphere-wall contacts through the same Law as particle pairs: the wall is
// body j with infinite mass (m* = m_i), the wall's velocity and no spin.
// History per (particle, wall) lives in the particle's wall-history field.
// With Shapes = true (scenes with ellipsoids) the geometry is chosen per
// particle: sphere or ellipsoid (contact/ellipsoid/ellipsoid_walls.hpp).
#include <algorithm>

#include "contact/ellipsoid/ellipsoid_walls.hpp"
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
class PlaneWallStage final : public Stage {
 public:
  std::string name() const override {
    return std::string("force.plane_walls") + (Shapes ? "[sphere|ellipsoid]" : "") + "<" + Law::name() + ">";
  }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    ParticleStore& p = s.particles;
    constexpr int H = Law::history_size;
    const int WH = p.wall_history_size();
    for (std::size_t w = 0; w < s.walls.planes.size(); ++w) {
      const PlaneWall& wall = s.walls.planes[w];
      if (wall.finite()) {  // a disc or annulus
        run_finite(s, w);
        continue;
      }
      // Each particle appears once per wall: rows are independent.
      const auto& near = s.neighbors.plane_near[w];
      const auto nn = static_cast<std::ptrdiff_t>(near.size());
      parallel_for(s.deterministic && use_threads(nn, 256), nn, [&](std::ptrdiff_t m) {
        const std::size_t i = near[static_cast<std::size_t>(m)];
        double* hist = H > 0 ? p.wall_history.data() + static_cast<std::size_t>(i) * WH + wall.history_slot * H : nullptr;
        contact::ContactGeometry g;
        bool touching;
        if constexpr (Shapes) {
          if (p.shape[i] == kEllipsoid) {
            g = contact::ellipsoid_plane_contact(p.x[i], p.form[i], p.semi_axes[i],
                                                 contact::PlaneWall{wall.point, wall.normal}, &touching);
          } else {
            touching = contact::sphere_plane(p.x[i], p.radius[i], wall.point, wall.normal, g);
          }
        } else {
          touching = contact::sphere_plane(p.x[i], p.radius[i], wall.point, wall.normal, g);
        }
        if (!touching) {
          if constexpr (H > 0) std::fill_n(hist, H, 0.0);
          return;
        }
        WallContact<Law, Law::needs_rotation || Shapes>::apply(p, i, g, wall.velocity, s.pairs(p.material[i], wall.material), s.clock.dt, hist);
      });
    }
  }

 private:
  static void run_finite(Scene& s, std::size_t w) {
    ParticleStore& p = s.particles;
    constexpr int H = Law::history_size;
    const int WH = p.wall_history_size();
    const PlaneWall& wall = s.walls.planes[w];
    const contact::Annulus a = wall.annulus();
    const auto& near = s.neighbors.plane_near[w];
    const auto nn = static_cast<std::ptrdiff_t>(near.size());
#pragma omp parallel for schedule(static) if (s.deterministic)
    for (std::ptrdiff_t m = 0; m < nn; ++m) {
      const std::size_t i = near[static_cast<std::size_t>(m)];
      double* hist = H > 0 ? p.wall_history.data() + static_cast<std::size_t>(i) * WH + wall.history_slot * H : nullptr;
      if constexpr (Shapes) {
        if (p.shape[i] == kEllipsoid) {
          ellipsoid_annulus(s, i, wall, a, hist);
          continue;
        }
      }
      contact::ContactGeometry g;
      if (!contact::sphere_annulus(p.x[i], p.radius[i], a, g)) {
        if constexpr (H > 0) std::fill_n(hist, H, 0.0);
        continue;
      }
      WallContact<Law, Law::needs_rotation || Shapes>::apply(p, i, g, wall.velocity, s.pairs(p.material[i], wall.material),
                                                            s.clock.dt, hist);
    }
  }

  // Up to two contacts (contact/ellipsoid/ellipsoid_walls.hpp), each in its
  // own slot (the wall has two: hist and hist + H). A lone contact (face or
  // rim), or a face contact beside a rim one, continues the slot that holds
  // history if only one does: it is the contact of the previous step, moved
  // (e.g. from the rim onto the face).
  static void ellipsoid_annulus(Scene& s, std::size_t i, const PlaneWall& wall, const contact::Annulus& a,
                                double* hist) {
    ParticleStore& p = s.particles;
    constexpr int H = Law::history_size;
    const contact::AnnulusContacts c =
        contact::ellipsoid_annulus_contacts({p.x[i], p.semi_axes[i], p.orientation[i]}, a);
    int slot[2] = {c.slot[0], c.slot[1]};
    if constexpr (H > 0) {
      // A lone contact, or a face contact beside a rim one, continues the
      // slot that holds history if only one does.
      if (c.count == 1 || c.face[0]) {
        auto held = [&](int k) {
          return std::any_of(hist + k * H, hist + (k + 1) * H, [](double v) { return v != 0.0; });
        };
        const bool h0 = held(0), h1 = held(1);
        if (h0 != h1) {
          slot[0] = h0 ? 0 : 1;
          slot[1] = 1 - slot[0];
        }
      }
    }
    bool used[2] = {false, false};
    for (int k = 0; k < c.count; ++k) {
      used[slot[k]] = true;
      WallContact<Law, true>::apply(p, i, c.g[k], wall.velocity, s.pairs(p.material[i], wall.material), s.clock.dt,
                                    H > 0 ? hist + slot[k] * H : nullptr);
    }
    if constexpr (H > 0)
      for (int k = 0; k < 2; ++k)
        if (!used[k]) std::fill_n(hist + k * H, H, 0.0);
  }
};

template <class Law, bool Shapes = false>
class CylinderWallStage final : public Stage {
 public:
  std::string name() const override {
    return std::string("force.cylinder_walls") + (Shapes ? "[sphere|ellipsoid]" : "") + "<" + Law::name() + ">";
  }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    ParticleStore& p = s.particles;
    constexpr int H = Law::history_size;
    const int WH = p.wall_history_size();
    for (std::size_t w = 0; w < s.walls.cylinders.size(); ++w) {
      const CylinderWall& wall = s.walls.cylinders[w];
      // Each particle appears once per wall: rows are independent.
      const auto& near = s.neighbors.cylinder_near[w];
      const auto nn = static_cast<std::ptrdiff_t>(near.size());
      parallel_for(s.deterministic && use_threads(nn, 256), nn, [&](std::ptrdiff_t m) {
        const std::size_t i = near[static_cast<std::size_t>(m)];
        double* hist = H > 0 ? p.wall_history.data() + static_cast<std::size_t>(i) * WH + wall.history_slot * H : nullptr;
        contact::ContactGeometry g;
        bool touching;
        if constexpr (Shapes) {
          if (p.shape[i] == kEllipsoid) {
            const auto& c = wall.surface;
            g = contact::ellipsoid_cylinder_contact(
                {p.x[i], p.semi_axes[i], p.orientation[i]},
                contact::CylinderWall{c.base, c.axis, c.radius, c.t_min, c.t_max, c.inside}, &touching);
          } else {
            touching = contact::sphere_cylinder(p.x[i], p.radius[i], wall.surface, g);
          }
        } else {
          touching = contact::sphere_cylinder(p.x[i], p.radius[i], wall.surface, g);
        }
        if (!touching) {
          if constexpr (H > 0) std::fill_n(hist, H, 0.0);
          return;
        }
        WallContact<Law, Law::needs_rotation || Shapes>::apply(p, i, g, wall.velocity, s.pairs(p.material[i], wall.material), s.clock.dt, hist);
      });
    }
  }
};

}  // namespace grains::sim
