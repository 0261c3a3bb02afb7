#pragma once
// Particle-particle contacts of spheres: geometry from contact/sphere.hpp,
// force from the composed Law. One instantiation per law composition; the
// kernel has no branches for absent effects.
#include <algorithm>
#include <memory>
#include <type_traits>

#include "contact/sphere.hpp"
#include "sim/laws/contact_law.hpp"
#include "sim/laws/entry_forces.hpp"
#include "sim/laws/probe_entries.hpp"
#include "sim/laws/sphere_lanes_stage.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {

template <class Law>
class PairContactStage final : public Stage {
 public:
  std::string name() const override { return "force.pair_contacts<" + Law::name() + ">"; }
  Phase phase() const override { return Phase::Force; }

  void run(Scene& s) override {
    if constexpr (kLanes) {
      // (A step the stress is measured, without ordered sums: the scalar loop, which probes each contact.)
      if (lanes_ && (s.deterministic || !s.stress_probe)) {
        sphere_pair_lanes(s, *batch_, e_, s.deterministic);
        return;
      }
    }
    if (s.deterministic)
      run_deferred(s);
    else if (s.stress_probe)  // a step the stress is measured
      run_direct<true>(s);
    else
      run_direct<false>(s);
  }

  std::vector<std::pair<std::string, double>> memory_parts() const override {
    return {{"ordered_sums_entry_forces", e_.bytes()}};
  }

 private:
  static constexpr int H = Law::history_size;
  static constexpr bool Rot = Law::needs_rotation;
  // Hertz–Mindlin with its spring and nothing else, the common dry law, runs
  // its touching pairs in lockstep lanes (sphere_lanes.hpp), bitwise as the
  // scalar law: every pair of the list as contact() below, batched
  // (sphere_lanes_stage.cpp).
  static constexpr bool kLanes = std::is_same_v<Law, ContactLaw<HertzNormal, SpringTangential, NoRolling, NoCohesion>>;
  // The contact of list entry k (row i): false when the pair does not touch.
  static GRAINS_INLINE bool contact(Scene& s, std::size_t i, std::uint32_t k, Vec3& force, Vec3& ti, Vec3& tj) {
    ParticleStore& p = s.particles;
    NeighborList& nl = s.neighbors;
    const std::size_t j = nl.partner[k];
    // Cheap rejection first: most list entries are within the skin but not
    // touching; their history is not even read unless the pair just separated.
    const Vec3 d = p.x[i] - p.x[j];
    const double d2 = d.squaredNorm();
    const double rc = nl.contact_distance(p, i, j);
    if (d2 >= rc * rc) {
      if constexpr (H > 0)
        if (nl.may_touch[k]) std::fill_n(nl.history.data() + static_cast<std::size_t>(k) * H, H, 0.0);
      nl.may_touch[k] = 0;
      return false;
    }
    nl.may_touch[k] = 1;
    double* hist = H > 0 ? nl.history.data() + static_cast<std::size_t>(k) * H : nullptr;
    // Sphere-sphere geometry (as contact::sphere_sphere, with R* and m*
    // from the list). The contact point lies on the line of centres, so
    // the lever arms are -li n and +lj n: one cross product each for the
    // relative velocity and the torques.
    const double ri = p.radius[i];
    contact::ContactGeometry g;
    const double dist = std::sqrt(d2);
    g.normal = dist > 0 ? Vec3(d * (1.0 / dist)) : Vec3(0, 0, 1);
    g.overlap = ri + p.radius[j] - dist;
    g.radius = NeighborList::pair_radius(p, i, j);
    const PairParams& pp = s.pairs(p.material[i], p.material[j]);
    const double li = ri - 0.5 * g.overlap, lj = p.radius[j] - 0.5 * g.overlap;
    Vec3 v_rel = p.v[i] - p.v[j];
    Vec3 w_rel = Vec3::Zero();
    if constexpr (Rot) {
      v_rel -= (li * p.omega[i] + lj * p.omega[j]).cross(g.normal);
      w_rel = p.omega[i] - p.omega[j];
    }
    const auto r = Law::evaluate(g, v_rel, w_rel, nl.pair_mass(p, i, j), pp, s.clock.dt, hist);
    force = r.force;
    if constexpr (Rot) {
      const Vec3 nxf = g.normal.cross(r.force);
      ti = r.rolling_torque - li * nxf;
      tj = -(r.rolling_torque + lj * nxf);
    }
    return true;
  }

  // Serial: forces added as they come (fastest; order = list order). With
  // Probe, each contact also goes into the stress probe.
  //
  // The entries that do not touch (most of a loose list) are passed over here,
  // with contact()'s test and its clearing of a spring, through pointers held
  // in registers: the stores of a touching entry (a byte, Eigen's packets) may
  // alias anything, so through p and nl each pointer would be loaded again at
  // every entry, on the path of the partner's position that a mispredicted
  // touch branch exposes. contact() tests a touching entry again (same bits).
  template <bool Probe>
  void run_direct(Scene& s) {
    ParticleStore& p = s.particles;
    NeighborList& nl = s.neighbors;
    const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
    const std::uint32_t* row_start = nl.row_start.data();
    const std::uint32_t* partner = nl.partner.data();
    const Vec3* x = p.x.data();
    const double* radius = p.radius.data();
    std::uint8_t* may_touch = nl.may_touch.data();
    [[maybe_unused]] double* history = nl.history.data();
    const double reach = nl.reach();
    Vec3 f, ti, tj;
    for (std::size_t i = 0; i < rows; ++i) {
      const Vec3 xi = x[i];
      const double ri = radius[i];
      const auto end = row_start[i + 1];
      for (auto k = row_start[i]; k < end; ++k) {
        {
          const std::size_t j = partner[k];
          const Vec3 d = xi - x[j];
          const double rc = ri + radius[j] + reach;  // nl.contact_distance
          if (d.squaredNorm() >= rc * rc) {
            if constexpr (H > 0)
              if (may_touch[k]) std::fill_n(history + static_cast<std::size_t>(k) * H, H, 0.0);
            may_touch[k] = 0;
            continue;
          }
        }
        if (!contact(s, i, k, f, ti, tj)) continue;
        const std::size_t j = nl.partner[k];
        p.f[i] += f;
        p.f[j] -= f;
        if constexpr (Rot) {
          p.torque[i] += ti;
          p.torque[j] += tj;
        }
        if constexpr (Probe) s.stress_probe->add_pair(0, p, i, j, f);
      }
    }
  }

  // Threads / deterministic: per-entry results, then an ordered gather.
  void run_deferred(Scene& s) {
    const NeighborList& nl = s.neighbors;
    const auto rows = static_cast<std::ptrdiff_t>(nl.row_start.empty() ? 0 : nl.row_start.size() - 1);
    e_.template resize<Rot>(nl.partner.size());
#pragma omp parallel for schedule(dynamic, 256)
    for (std::ptrdiff_t ii = 0; ii < rows; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        Vec3 f, ti, tj;
        if (contact(s, i, k, f, ti, tj))
          e_.template set<Rot>(k, f, ti, tj);
        else
          e_.template zero<Rot>(k, k + 1);
      }
    }
    gather_entry_forces<Rot>(s.particles, nl, e_);
    if (s.stress_probe) probe_entries<Rot>(*s.stress_probe, s.particles, nl, e_);
  }

  EntryForces e_;
  const bool lanes_ = kLanes && sphere_lanes_enabled();  // GRAINS_SIMD=scalar: the scalar loop
  std::unique_ptr<SphereContactBatch> batch_ = kLanes ? std::make_unique<SphereContactBatch>() : nullptr;
};

}  // namespace grains::sim
