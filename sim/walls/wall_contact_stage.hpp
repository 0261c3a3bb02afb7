#pragma once
#include "contact/contact_geometry.hpp"
// Particle-wall contacts of every wall kind through the same Law as particle
// pairs: the wall is body j with infinite mass (m* = m_i), the velocity of
// its surface at the contact point and no spin. One stage for all walls:
// each kind supplies its contacts (wall_kind.hpp), this loop evaluates them
// over the wall's near list, keeps the history per (particle, wall slot) in
// the particle's wall-history field (and, for tagged kinds, the contact's
// normal and a mask of the slots held in wall_tags) and clears the slots a
// particle no longer uses. With
// Shapes = true (scenes with ellipsoids) the geometry is chosen per
// particle: sphere or ellipsoid. When the scene measures wall loads, each
// wall's force and torque are summed (per thread, then in thread order).
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>

#include <omp.h>

#include "sim/laws/contact_law.hpp"
#include "sim/scene/stage.hpp"
#include "sim/state/parallel_for.hpp"

namespace grains::sim {

template <class Law, bool Rotation = Law::needs_rotation>
struct WallContact {
  /// Applies the contact to particle i; returns the force on it (and, when
  /// asked, the rolling torque and the normal stiffness and dashpot).
  static GRAINS_INLINE Vec3 apply(ParticleStore& p, std::size_t i, const contact::ContactGeometry& g,
                                  const Vec3& wall_velocity, const PairParams& pp, double dt, double* hist,
                                  Vec3* rolling = nullptr, double* stiffness = nullptr, double* damping = nullptr) {
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
    if constexpr (Rotation) {
      p.torque[i] += ci.cross(r.force) + r.rolling_torque;
      if (rolling) *rolling = r.rolling_torque;
    }
    if (stiffness) *stiffness = r.stiffness;
    if (damping) *damping = r.damping;
    return r.force;
  }
};

/// A particle's history slots of one wall, as a kind's contacts() sees them.
template <int H, bool Tagged, bool Beyond = false>
struct WallSlots {
  double* hist;  // H doubles per slot (null when H = 0)
  double* tags;  // tagged kinds with history: the mask of the slots held, then 3 doubles per slot
  int n = 1;     // slots
  /// How far beyond touching a contact may hold (laws with Beyond, JKR).
  double reach = 0;
  /// The radius a kind looks for contacts of a sphere of radius r with: r
  /// grown by the reach for such a law, r itself (no code) for the others.
  GRAINS_INLINE double grown(double r) const {
    if constexpr (Beyond)
      return r + reach;
    else
      return r;
  }
  static constexpr bool keeps_history() { return H > 0; }
  bool held(int k) const {
    if constexpr (H == 0) {
      (void)k;
      return false;
    } else if constexpr (Tagged) {
      return (mask() >> k & 1u) != 0;
    } else {
      return std::any_of(hist + k * H, hist + (k + 1) * H, [](double v) { return v != 0.0; });
    }
  }
  // The mask first: a row with one contact reads one stretch (mask, its normal).
  double* tag(int k) const { return tags + 1 + 3 * k; }
  unsigned mask() const { return static_cast<unsigned>(tags[0]); }
  void set_mask(unsigned m) const { tags[0] = static_cast<double>(m); }
};

template <class Law, bool Shapes = false>
class WallStage final : public Stage {
 public:
  std::string name() const override {
    return std::string("force.walls") + (Shapes ? "[sphere|ellipsoid]" : "") + "<" + Law::name() + ">";
  }
  Phase phase() const override { return Phase::Force; }
  void run(Scene& s) override {
    // Loads (and the stress probe's contacts) only when measured.
    const bool loads = !s.wall_loads.empty() || s.stress_probe;
    s.walls.for_each([&](const auto& wall, std::size_t w) {
      const auto& items = w < s.neighbors.wall_items.size() ? s.neighbors.wall_items[w] : no_items_;
      if (loads && s.wall_loads.empty())
        run_wall<true>(s, wall, s.neighbors.wall_near[w], items, unused_);
      else if (loads)
        run_wall<true>(s, wall, s.neighbors.wall_near[w], items, s.wall_loads[w]);
      else
        run_wall<false>(s, wall, s.neighbors.wall_near[w], items, s.wall_loads.empty() ? unused_ : s.wall_loads[w]);
    });
  }

 private:
  template <bool Loads, class K>
  void run_wall(Scene& s, const K& wall, const std::vector<std::uint32_t>& near, const NearItems& items,
                WallLoad& load) {
    ParticleStore& p = s.particles;
    constexpr int H = Law::history_size;
    constexpr bool Tagged = K::tagged && H > 0;
    const int WH = p.wall_history_size();
    const int WT = p.wall_tag_size();
    const int slots = wall.history_slots;
    constexpr bool Beyond = holds_beyond_touching<Law>();
    const double reach = s.neighbors.reach();
    const auto nn = static_cast<std::ptrdiff_t>(near.size());
    const bool threads = s.deterministic && use_threads(nn, 256);
    Vec3 point{0, 0, 0};
    if constexpr (Loads) {
      if constexpr (requires { wall.load_point(); })
        point = wall.load_point();
      else
        point = wall.position();
      partial_.assign(threads ? static_cast<std::size_t>(omp_get_max_threads()) : 1, WallLoad{});
    }
    // The fields' addresses, read once (the contacts call functions the
    // compiler cannot see through, after which it would read them again).
    // (None without rows: the fields may be empty, their data() null.)
    double* const hist0 = H > 0 && nn > 0 ? p.wall_history.data() + wall.history_slot * H : nullptr;
    double* const tags0 = Tagged && nn > 0 ? p.wall_tags.data() + wall.tag_offset : nullptr;
    // A kind with near items has a range of them for every row (near_list);
    // the others none.
    if (K::near_items && items.start.size() != near.size() + 1)
      throw std::logic_error("wall " + wall.name + ": its near items do not match its near list");
    const std::uint32_t* const item = items.items.data();
    const std::uint32_t* const item_start = items.start.data();
    const std::uint32_t* const row_particle = near.data();
    // Each particle appears once per wall: rows are independent. (The row's
    // constants are captured by value: by reference each read would go
    // through the closure, again after every call the compiler cannot see.)
    parallel_for(threads, nn, [&, row_particle, hist0, tags0, item, item_start, WH, WT, slots, reach](std::ptrdiff_t m) {
      const std::size_t i = row_particle[m];
      if constexpr (H > 0) {  // a few rows ahead: the rows' particles are scattered
        if (m + 8 < nn) {
          const std::size_t ia = row_particle[m + 8];
          __builtin_prefetch(hist0 + ia * static_cast<std::size_t>(WH));
          if constexpr (Tagged)  // the mask and the first slot's normal
            __builtin_prefetch(tags0 + ia * static_cast<std::size_t>(WT) + 3);
        }
      }
      double* hist = H > 0 ? hist0 + i * static_cast<std::size_t>(WH) : nullptr;
      double* tags = Tagged ? tags0 + i * static_cast<std::size_t>(WT) : nullptr;
      const WallSlots<H, Tagged, Beyond> sl{hist, tags, slots, reach};
      unsigned used = 0;  // the slots a contact used this step
      const std::span<const std::uint32_t> row =
          K::near_items ? std::span<const std::uint32_t>(item + item_start[m], item + item_start[m + 1])
                        : std::span<const std::uint32_t>();
      wall.template contacts<Shapes>(p, i, row, sl,
                                     [&](const contact::ContactGeometry& found, int slot) {
        // (A kind found the contact of the sphere grown by the reach: the overlap and R* are the sphere's.)
        [[maybe_unused]] contact::ContactGeometry grown;
        if constexpr (Beyond) {
          grown = found;
          grown.overlap -= reach;
          grown.radius = p.radius[i];
        }
        const contact::ContactGeometry& g = Beyond ? grown : found;
        [[maybe_unused]] std::array<double, Tagged ? H : 1> spare;  // a contact beyond the slots: no history
        double* h = nullptr;
        if constexpr (H > 0) {
          if (Tagged && slot < 0) {
            spare.fill(0.0);
            h = spare.data();
          } else {
            used |= 1u << slot;
            h = hist + slot * H;
          }
        }
        Vec3 rolling{0, 0, 0};
        double k = 0, c = 0;
        const Vec3 f = WallContact<Law, Law::needs_rotation || Shapes>::apply(
            p, i, g, wall.surface_velocity(g.point), s.pairs(p.material[i], wall.material), s.clock.dt, h, &rolling,
            Loads ? &k : nullptr, Loads ? &c : nullptr);
        if constexpr (Loads) {
          WallLoad& l = partial_[threads ? static_cast<std::size_t>(omp_get_thread_num()) : 0];
          l.force -= f;
          l.torque -= (g.point - point).cross(f) + rolling;
          l.stiffness += k;
          l.damping += c;
          if (s.stress_probe)  // the branch from the contact point to the centre
            s.stress_probe->add(threads ? omp_get_thread_num() : 0, p.x[i], f, p.x[i] - g.point);
        }
      });
      if constexpr (H > 0) {
        if (!Tagged && slots == 1) {  // most walls: one fill of known size
          if (used == 0) std::fill_n(hist, H, 0.0);
        } else if constexpr (Tagged) {  // only the slots just left are cleared
          const unsigned held = sl.mask();
          if (held & ~used) {
            for (unsigned m = held & ~used; m != 0; m &= m - 1) {
              const int k = __builtin_ctz(m);
              std::fill_n(hist + k * H, H, 0.0);
              std::fill_n(sl.tag(k), 3, 0.0);
            }
            sl.set_mask(held & used);
          }
        } else {
          for (int k = 0; k < slots; ++k)
            if (!(used >> k & 1u)) std::fill_n(hist + k * H, H, 0.0);
        }
      }
    });
    if constexpr (Loads) {
      load = WallLoad{};
      for (const auto& l : partial_) load.force += l.force, load.torque += l.torque, load.stiffness += l.stiffness, load.damping += l.damping;
    }
  }

  std::vector<WallLoad> partial_;
  NearItems no_items_;
  WallLoad unused_;
};

}  // namespace grains::sim
