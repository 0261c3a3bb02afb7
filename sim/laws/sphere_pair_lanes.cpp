// The Hertz–Mindlin force loop of sphere pairs in lanes: see
// sphere_pair_lanes.hpp. Moved here from pair_contact_stage.hpp unchanged.
#include "sim/laws/sphere_pair_lanes.hpp"

#include <algorithm>

#include "sim/laws/probe_entries.hpp"
#include "sim/scene/scene.hpp"

namespace grains::sim {

namespace {

// From this many particles (owned and ghosts: about 6 MB of the fields a
// pair reads) the lanes prefetch the partners' fields; below, the cache
// holds them and the prefetches only cost instructions.
constexpr std::size_t kPrefetchFrom = std::size_t{1} << 15;

void copy_lane(SphereContactBatch& b, int from, int to) {
  using B = SphereContactBatch;
  static constexpr double(B::*inputs[])[B::kSize] = {
      &B::dx,  &B::dy,  &B::dz, &B::d2, &B::ri, &B::rj, &B::vx, &B::vy,  &B::vz, &B::wix, &B::wiy, &B::wiz, &B::wjx,
      &B::wjy, &B::wjz, &B::R,  &B::m,  &B::E,  &B::G,  &B::a,  &B::tdr, &B::mu, &B::hx,  &B::hy,  &B::hz};
  for (auto a : inputs) (b.*a)[to] = (b.*a)[from];
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
void lanes_rows(Scene& s, SphereContactBatch& b, std::size_t row_begin, std::size_t row_end, Apply&& apply) {
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

// Serial: forces added in list order, as run_direct's. Deterministic (and
// threaded): per-entry results in parallel over rows, then the ordered
// gather, as run_deferred's.
template <bool Deferred>
void run_lanes(Scene& s, SphereContactBatch& batch, EntryForces& e) {
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
      lanes_rows<true>(s, batch, 0, rows, add);
    else
      lanes_rows<false>(s, batch, 0, rows, add);
  } else {
    e.resize<true>(nl.partner.size());
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
          for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) e.zero<true>(k);
        auto put = [&](int l, std::size_t, std::uint32_t k, const SphereContactBatch& bb) {
          e.f[k] = Vec3(bb.fx[l], bb.fy[l], bb.fz[l]);
          e.ti[k] = Vec3(bb.tix[l], bb.tiy[l], bb.tiz[l]);
          e.tj[k] = Vec3(bb.tjx[l], bb.tjy[l], bb.tjz[l]);
        };
        if (prefetch)
          lanes_rows<true>(s, b, lo, hi, put);
        else
          lanes_rows<false>(s, b, lo, hi, put);
      }
    }
    gather_entry_forces<true>(p, nl, e);
    if (s.stress_probe) probe_entries(*s.stress_probe, p, nl, e.f);
  }
}

}  // namespace

void sphere_pair_lanes(Scene& s, SphereContactBatch& batch, EntryForces& e, bool deferred) {
  if (deferred)
    run_lanes<true>(s, batch, e);
  else
    run_lanes<false>(s, batch, e);
}

}  // namespace grains::sim
