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
#include "sim/laws/sphere_lanes.hpp"
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
        if (s.deterministic)
          run_lanes<true>(s);
        else
          run_lanes<false>(s);
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

 private:
  static constexpr int H = Law::history_size;
  static constexpr bool Rot = Law::needs_rotation;
  // Hertz–Mindlin with its spring and nothing else, the common dry law, runs
  // its touching pairs in lockstep lanes (sphere_lanes.hpp), bitwise as the
  // scalar law: every pair of the list as contact() below, batched.
  static constexpr bool kLanes = std::is_same_v<Law, ContactLaw<HertzNormal, SpringTangential, NoRolling, NoCohesion>>;
  // From this many particles (owned and ghosts: about 6 MB of the fields a
  // pair reads) the lanes prefetch the partners' fields; below, the cache
  // holds them and the prefetches only cost instructions.
  static constexpr std::size_t kPrefetchFrom = std::size_t{1} << 15;

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
      Vec3 dummy;
      for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        if constexpr (Rot) {
          if (!contact(s, i, k, e_.f[k], e_.ti[k], e_.tj[k])) e_.template zero<Rot>(k);
        } else {
          if (!contact(s, i, k, e_.f[k], dummy, dummy)) e_.template zero<Rot>(k);
        }
      }
    }
    gather_entry_forces<Rot>(s.particles, nl, e_);
    if (s.stress_probe) probe_entries(*s.stress_probe, s.particles, nl, e_.f);
  }

  // Lanes: the touching entries of rows [row_begin, row_end) go into batches
  // (the others' history is cleared as in contact()); each full batch is
  // computed and handed to apply(lane, i, k, batch) in list order. The list
  // is read in two passes per batch, so that neither has a branch that the
  // processor cannot predict: the first tests every entry and writes its
  // geometry into the next free lane, which only a touching entry keeps (a
  // quarter of the entries in a dense bed do not touch, in no pattern); the
  // second gathers the motion, constants and springs of the kept lanes.
  template <bool Prefetch, class Apply>
  static void lanes_rows(Scene& s, SphereContactBatch& b, std::size_t row_begin, std::size_t row_end,
                         Apply&& apply) {
    ParticleStore& p = s.particles;
    NeighborList& nl = s.neighbors;
    std::uint32_t row_of[SphereContactBatch::kSize], entry_of[SphereContactBatch::kSize];
    b.dt = s.clock.dt;
    b.count = 0;
    auto flush = [&] {
      if (b.count == 0) return;
      for (int l = 0; l < b.count; ++l) {
        const std::size_t i = row_of[l], k = entry_of[l], j = nl.partner[k];
        const Vec3 v = p.v[i] - p.v[j];
        b.vx[l] = v.x(), b.vy[l] = v.y(), b.vz[l] = v.z();
        b.wix[l] = p.omega[i].x(), b.wiy[l] = p.omega[i].y(), b.wiz[l] = p.omega[i].z();
        b.wjx[l] = p.omega[j].x(), b.wjy[l] = p.omega[j].y(), b.wjz[l] = p.omega[j].z();
        b.R[l] = NeighborList::pair_radius(p, i, j), b.m[l] = nl.pair_mass(p, i, j);
        const PairParams& pp = s.pairs(p.material[i], p.material[j]);
        b.E[l] = pp.E_eff, b.G[l] = pp.G_eff, b.a[l] = pp.damping, b.tdr[l] = pp.tangential_damping_ratio;
        b.mu[l] = pp.friction;
        const double* h = nl.history.data() + k * 3;
        b.hx[l] = h[0], b.hy[l] = h[1], b.hz[l] = h[2];
      }
      for (int l = b.count; l % 4 != 0; ++l) copy_lane(b, b.count - 1, l);  // padding: a finite contact
      hertz_mindlin_lanes(b);
      for (int l = 0; l < b.count; ++l) {
        double* h = nl.history.data() + static_cast<std::size_t>(entry_of[l]) * 3;
        h[0] = b.hx[l], h[1] = b.hy[l], h[2] = b.hz[l];
        apply(l, row_of[l], entry_of[l], b);
      }
      b.count = 0;
    };
    // Prefetches (no effect on results), in scenes larger than the cache
    // (kPrefetchFrom): there the partner of an entry lies up to a layer of
    // cells ahead in memory, not yet read. The first pass asks for the
    // position and radius of the partner kPrefetch entries ahead, and for
    // each entry the fields the second pass and the force sums will read if
    // it touches. (Measured, bench/RESULTS.md: -30 % time per pair in a bed
    // of 10^5 grains, +15 % in one of 10^4 that the cache holds.)
    constexpr std::uint32_t kPrefetch = 16;
    const auto end = row_end > row_begin ? nl.row_start[row_end] : 0;
    for (std::size_t i = row_begin; i < row_end; ++i)
      for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        if constexpr (Prefetch) {
          if (k + kPrefetch < end) {
            const std::size_t ahead = nl.partner[k + kPrefetch];
            __builtin_prefetch(&p.x[ahead]);
            __builtin_prefetch(&p.radius[ahead]);
          }
        }
        const std::size_t j = nl.partner[k];
        const Vec3 d = p.x[i] - p.x[j];
        const double d2 = d.squaredNorm();
        const double rc = nl.contact_distance(p, i, j);
        const bool touch = !(d2 >= rc * rc);
        // A pair that just came apart: its spring goes (rarely true: predicted).
        if (!touch & (nl.may_touch[k] != 0)) std::fill_n(nl.history.data() + static_cast<std::size_t>(k) * 3, 3, 0.0);
        nl.may_touch[k] = touch;
        const int l = b.count;
        b.dx[l] = d.x(), b.dy[l] = d.y(), b.dz[l] = d.z(), b.d2[l] = d2;
        b.ri[l] = p.radius[i], b.rj[l] = p.radius[j];
        row_of[l] = static_cast<std::uint32_t>(i), entry_of[l] = k;
        if constexpr (Prefetch) {  // (for every entry: a branch on touch would be mispredicted)
          __builtin_prefetch(&p.v[j]);
          __builtin_prefetch(&p.omega[j]);
          __builtin_prefetch(&p.mass[j]);
          __builtin_prefetch(&p.f[j], 1);
          __builtin_prefetch(&p.torque[j], 1);
        }
        b.count += touch;
        if (b.count == SphereContactBatch::kSize) flush();
      }
    flush();
  }

  static void copy_lane(SphereContactBatch& b, int from, int to) {
    using B = SphereContactBatch;
    static constexpr double (B::*inputs[])[B::kSize] = {
        &B::dx, &B::dy, &B::dz, &B::d2, &B::ri, &B::rj, &B::vx, &B::vy, &B::vz, &B::wix, &B::wiy, &B::wiz,
        &B::wjx, &B::wjy, &B::wjz, &B::R, &B::m, &B::E, &B::G, &B::a, &B::tdr, &B::mu, &B::hx, &B::hy, &B::hz};
    for (auto a : inputs) (b.*a)[to] = (b.*a)[from];
  }

  // Serial: forces added in list order, as run_direct's. Deterministic (and
  // threaded): per-entry results in parallel over rows, then the ordered
  // gather, as run_deferred's.
  template <bool Deferred>
  void run_lanes(Scene& s) {
    ParticleStore& p = s.particles;
    const NeighborList& nl = s.neighbors;
    const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
    if constexpr (!Deferred) {
      auto add = [&](int l, std::size_t i, std::uint32_t k, const SphereContactBatch& b) {
        const std::size_t j = nl.partner[k];
        const Vec3 f(b.fx[l], b.fy[l], b.fz[l]);
        p.f[i] += f;
        p.f[j] -= f;
        p.torque[i] += Vec3(b.tix[l], b.tiy[l], b.tiz[l]);
        p.torque[j] += Vec3(b.tjx[l], b.tjy[l], b.tjz[l]);
      };
      if (p.size() >= kPrefetchFrom)
        lanes_rows<true>(s, *batch_, 0, rows, add);
      else
        lanes_rows<false>(s, *batch_, 0, rows, add);
    } else {
      e_.template resize<Rot>(nl.partner.size());
      const auto n_rows = static_cast<std::ptrdiff_t>(rows);
      constexpr std::ptrdiff_t chunk = 256;
      const bool prefetch = p.size() >= kPrefetchFrom;
#pragma omp parallel
      {
        SphereContactBatch b;
#pragma omp for schedule(dynamic, 1)
        for (std::ptrdiff_t r0 = 0; r0 < n_rows; r0 += chunk) {
          const auto lo = static_cast<std::size_t>(r0), hi = static_cast<std::size_t>(std::min(r0 + chunk, n_rows));
          for (std::size_t i = lo; i < hi; ++i)  // entries not touching stay zero
            for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) e_.template zero<Rot>(k);
          auto put = [&](int l, std::size_t, std::uint32_t k, const SphereContactBatch& bb) {
            e_.f[k] = Vec3(bb.fx[l], bb.fy[l], bb.fz[l]);
            e_.ti[k] = Vec3(bb.tix[l], bb.tiy[l], bb.tiz[l]);
            e_.tj[k] = Vec3(bb.tjx[l], bb.tjy[l], bb.tjz[l]);
          };
          if (prefetch)
            lanes_rows<true>(s, b, lo, hi, put);
          else
            lanes_rows<false>(s, b, lo, hi, put);
        }
      }
      gather_entry_forces<Rot>(p, nl, e_);
      if (s.stress_probe) probe_entries(*s.stress_probe, p, nl, e_.f);
    }
  }

  EntryForces e_;
  const bool lanes_ = kLanes && sphere_lanes_enabled();  // GRAINS_SIMD=scalar: the scalar loop
  std::unique_ptr<SphereContactBatch> batch_ = kLanes ? std::make_unique<SphereContactBatch>() : nullptr;
};

}  // namespace grains::sim
