// The Hertz–Mindlin force loop of sphere pairs in lanes: see
// sphere_lanes_stage.hpp.
#include "sim/laws/sphere_lanes_stage.hpp"

#include <algorithm>

#include "sim/laws/probe_entries.hpp"
#include "sim/laws/sphere_lanes_screen.hpp"
#include "sim/scene/scene.hpp"

namespace grains::sim {

namespace {

// From this many particles (owned and ghosts: about 6 MB of the fields a
// pair reads) the lanes prefetch the partners' fields, and the ordered
// sums' gather its records; below, the cache holds them and the prefetches
// only cost instructions.
constexpr std::size_t kPrefetchFrom = std::size_t{1} << 15;

void copy_lane(SphereContactBatch& b, int from, int to) {
  using B = SphereContactBatch;
  static constexpr double(B::*inputs[])[B::kRoom] = {
      &B::dx,  &B::dy,  &B::dz, &B::d2, &B::ri, &B::rj, &B::vx, &B::vy,  &B::vz, &B::wix, &B::wiy, &B::wiz, &B::wjx,
      &B::wjy, &B::wjz, &B::R,  &B::m,  &B::E,  &B::G,  &B::a,  &B::tdr, &B::mu, &B::hx,  &B::hy,  &B::hz};
  for (auto a : inputs) (b.*a)[to] = (b.*a)[from];
}

// Lanes: the touching entries of rows [row_begin, row_end) go into batches
// (the others' history is cleared as in contact()); each full batch is
// computed and handed to apply(lane, i, j, k, batch) in list order. The list
// is read in two passes per batch, so that neither has a branch that the
// processor cannot predict: the first tests every entry and writes its
// geometry into the next free lane, which only a touching entry keeps (a
// quarter of the entries in a dense bed do not touch, in no pattern); the
// second gathers the motion, constants and springs of the kept lanes.
// (Gathering everything in the first pass, for every entry, measured 3 %
// slower on the 10^4 bed: bench/RESULTS.md, 2026-11-29.) With AVX-512F the
// first pass runs eight entries at a time (sphere_lanes_screen_avx512.cpp)
// and the second is fused into the kernel (bench/RESULTS.md, 2026-12-02:
// with the kernel's own change, the pair stage in half the time on the 10^4
// bed); with AVX2 likewise, four entries at a time (2026-12-02).
//
// Every field is read through a pointer taken before the loops, apply is a
// copy (a lambda holding its target pointers) and the lane count a local:
// the stores of a byte (may_touch) or of a double (the batch, the forces)
// may alias anything reachable through the particle store, the list or a
// reference, so through them each pointer would be loaded again at every
// entry. The arithmetic is the scalar law's, in its order (R* and m* as
// NeighborList::pair_radius and pair_mass compute them).
template <bool Prefetch, class Apply>
void lanes_rows(Scene& s, SphereContactBatch& b, std::size_t row_begin, std::size_t row_end, Apply apply) {
  constexpr int kSize = SphereContactBatch::kSize, kRoom = SphereContactBatch::kRoom;
  const ParticleStore& p = s.particles;
  NeighborList& nl = s.neighbors;
  const std::uint32_t* const row_start = nl.row_start.data();
  const std::uint32_t* const partner = nl.partner.data();
  std::uint8_t* const may_touch = nl.may_touch.data();
  double* const history = nl.history.data();
  const Vec3* const x = p.x.data();
  const Vec3* const v = p.v.data();
  const Vec3* const w = p.omega.data();
  const double* const radius = p.radius.data();
  const double* const mass = p.mass.data();
  const std::int32_t* const material = p.material.data();
  const double reach = nl.reach();
  const bool frozen = nl.frozen();
  const PairTable& pairs = s.pairs;
  // One material (the common case): the pair constants are the same in every
  // lane, written once here rather than at every contact.
  const bool one_material = pairs.size() == 1;
  if (one_material) {
    const PairParams& pp = pairs(0, 0);
    std::fill_n(b.E, kRoom, pp.E_eff), std::fill_n(b.G, kRoom, pp.G_eff), std::fill_n(b.a, kRoom, pp.damping);
    std::fill_n(b.tdr, kRoom, pp.tangential_damping_ratio), std::fill_n(b.mu, kRoom, pp.friction);
  }
  alignas(32) std::uint32_t row_of[kRoom], entry_of[kRoom], partner_of[kRoom];
  alignas(64) double mi[kSize], mj[kSize];  // (the scalar second pass: at most kSize lanes)
  int n = 0;                                // lanes filled
  b.dt = s.clock.dt;
  // The list passes eight entries at a time where the processor has
  // AVX-512F, four with AVX2 (sphere_lanes_screen.hpp); the second one,
  // fused into the kernel, with one material and no frozen grains only
  // (else the scalar one below).
  static_assert(sizeof(Vec3) == 3 * sizeof(double));
  const SphereScreenFn screen = sphere_screen();
  const SphereGatheredKernelFn gathered = one_material && !frozen ? sphere_kernel_gathered() : nullptr;
  auto doubles = [](const Vec3* a) { return reinterpret_cast<const double*>(a); };
  const SphereScreenFields in{row_start,
                              nl.row_start.empty() ? 0 : nl.row_start.size() - 1,
                              partner,
                              nl.partner.size(),
                              may_touch,
                              history,
                              doubles(x),
                              radius,
                              doubles(v),
                              doubles(w),
                              mass,
                              doubles(p.f.data()),
                              doubles(p.torque.data()),
                              reach,
                              Prefetch,
                              row_of,
                              entry_of,
                              partner_of};
  // (Inlined at both calls: a call would keep the lane count in memory, its
  // every increment a store and a load on the path of the next entry.)
  // A batch is computed kSize lanes at a time: the AVX-512 screen may have
  // filled up to kPad - 1 lanes more, which move to the front of the next
  // batch (so the kernel computes no padding lanes but at the end).
  auto flush = [&]() __attribute__((always_inline)) {
    if (n == 0) return;
    const int m = n < kSize ? n : kSize;
    if (!gathered) {
      for (int l = 0; l < m; ++l) {
        const std::size_t i = row_of[l], k = entry_of[l], j = partner_of[l];
        const Vec3 dv = v[i] - v[j];
        b.vx[l] = dv.x(), b.vy[l] = dv.y(), b.vz[l] = dv.z();
        b.wix[l] = w[i].x(), b.wiy[l] = w[i].y(), b.wiz[l] = w[i].z();
        b.wjx[l] = w[j].x(), b.wjy[l] = w[j].y(), b.wjz[l] = w[j].z();
        if (frozen)
          b.m[l] = nl.pair_mass(p, i, j);
        else
          mi[l] = mass[i], mj[l] = mass[j];
        if (!one_material) {
          const PairParams& pp = pairs(material[i], material[j]);
          b.E[l] = pp.E_eff, b.G[l] = pp.G_eff, b.a[l] = pp.damping, b.tdr[l] = pp.tangential_damping_ratio;
          b.mu[l] = pp.friction;
        }
        const double* h = history + k * 3;
        b.hx[l] = h[0], b.hy[l] = h[1], b.hz[l] = h[2];
      }
      // R* = ri rj / (ri + rj), m* = mi mj / (mi + mj) (with frozen grains the
      // list's pair_mass, above): lane by lane, as the list's pair_radius and pair_mass.
      for (int l = 0; l < m; ++l) b.R[l] = b.ri[l] * b.rj[l] / (b.ri[l] + b.rj[l]);
      if (!frozen)
        for (int l = 0; l < m; ++l) b.m[l] = mi[l] * mj[l] / (mi[l] + mj[l]);
    }
    b.count = m;
    for (int l = m; l % SphereContactBatch::kPad != 0;
         ++l) {  // padding: a finite contact (the gathered kernel reads its indices too)
      copy_lane(b, m - 1, l);
      row_of[l] = row_of[m - 1], entry_of[l] = entry_of[m - 1], partner_of[l] = partner_of[m - 1];
    }
    if (gathered)
      gathered(in, b);
    else
      hertz_mindlin_lanes(b);
    for (int l = 0; l < m; ++l) {
      double* h = history + static_cast<std::size_t>(entry_of[l]) * 3;
      h[0] = b.hx[l], h[1] = b.hy[l], h[2] = b.hz[l];
      apply(l, row_of[l], partner_of[l], entry_of[l], b);
    }
    // (m = kSize, a multiple of kPad, whenever lanes remain: no padding
    // overwrote them.)
    for (int l = m; l < n; ++l) {
      const int to = l - m;
      b.dx[to] = b.dx[l], b.dy[to] = b.dy[l], b.dz[to] = b.dz[l], b.d2[to] = b.d2[l];
      b.ri[to] = b.ri[l], b.rj[to] = b.rj[l];
      row_of[to] = row_of[l], entry_of[to] = entry_of[l], partner_of[to] = partner_of[l];
    }
    n -= m;
  };
  // Prefetches (no effect on results), in scenes larger than the cache
  // (kPrefetchFrom): there the partner of an entry lies up to a layer of
  // cells ahead in memory, not yet read. The first pass asks for the
  // position and radius of the partner kPrefetch entries ahead, and for
  // each entry the fields the second pass and the force sums will read if
  // it touches. (Measured, bench/RESULTS.md: -30 % time per pair in a bed
  // of 10^5 grains, +15 % in one of 10^4 that the cache holds.)
  constexpr std::uint32_t kPrefetch = 16;
  [[maybe_unused]] const Vec3* const f = p.f.data();
  [[maybe_unused]] const Vec3* const torque = p.torque.data();
  if (screen) {
    std::size_t i = row_begin;
    std::uint32_t k = 0;
    while (i < row_end) {
      n = screen(in, b, n, i, k, row_end, Prefetch);
      if (n >= kSize) flush();
    }
    while (n > 0) flush();
    return;
  }
  const auto end = row_end > row_begin ? row_start[row_end] : 0;
  for (std::size_t i = row_begin; i < row_end; ++i) {
    const Vec3 xi = x[i];
    const double ri = radius[i];
    const auto row_end_k = row_start[i + 1];
    for (auto k = row_start[i]; k < row_end_k; ++k) {
      if constexpr (Prefetch) {
        if (k + kPrefetch < end) {
          const std::size_t ahead = partner[k + kPrefetch];
          __builtin_prefetch(&x[ahead]);
          __builtin_prefetch(&radius[ahead]);
        }
      }
      const std::uint32_t j = partner[k];
      const Vec3 d = xi - x[j];
      const double d2 = d.squaredNorm();
      const double rj = radius[j];
      const double rc = ri + rj + reach;  // nl.contact_distance
      const bool touch = !(d2 >= rc * rc);
      // A pair that just came apart: its spring goes (rarely true: predicted).
      if (!touch & (may_touch[k] != 0)) std::fill_n(history + static_cast<std::size_t>(k) * 3, 3, 0.0);
      may_touch[k] = touch;
      b.dx[n] = d.x(), b.dy[n] = d.y(), b.dz[n] = d.z(), b.d2[n] = d2;
      b.ri[n] = ri, b.rj[n] = rj;
      row_of[n] = static_cast<std::uint32_t>(i), entry_of[n] = k, partner_of[n] = j;
      if constexpr (Prefetch) {  // (for every entry: a branch on touch would be mispredicted)
        __builtin_prefetch(&v[j]);
        __builtin_prefetch(&w[j]);
        __builtin_prefetch(&mass[j]);
        __builtin_prefetch(&f[j], 1);
        __builtin_prefetch(&torque[j], 1);
      }
      n += touch;
      if (n == kSize) flush();
    }
  }
  flush();
}

// Rows [lo, hi) of the deferred path: each entry's force and torques into
// its slots (zero for the entries not touching). A function of its own:
// inlined into the OpenMP region, whose variables the outlined body reaches
// through a pointer, the loops kept their counters and pointers on the stack
// (2 ranks on the 10^4 bed, 2026-11-29).
template <bool Prefetch>
__attribute__((noinline)) void deferred_rows(Scene& s, SphereContactBatch& b, EntryForces& e, std::size_t lo,
                                             std::size_t hi) {
  // The compact layout: the rows' entries not touching read the zero record;
  // the touching ones get records from the rows' first entry + 1 on, in
  // list order (a chunk of rows holds at most as many contacts as entries).
  const std::uint32_t k0 = s.neighbors.row_start[lo];
  e.clear_slots(k0, s.neighbors.row_start[hi]);
  // Where the lanes prefetch (a bed the cache does not hold) the records go
  // past the cache: the gather reads them only after every row.
  auto put = [&e, rec = k0 + 1](int l, std::size_t, std::size_t, std::uint32_t k,
                                const SphereContactBatch& bb) mutable {
    const Vec3 f(bb.fx[l], bb.fy[l], bb.fz[l]), ti(bb.tix[l], bb.tiy[l], bb.tiz[l]), tj(bb.tjx[l], bb.tjy[l], bb.tjz[l]);
    if constexpr (Prefetch)
      e.put_stream<true>(rec++, k, f, ti, tj);
    else
      e.put<true>(rec++, k, f, ti, tj);
  };
  lanes_rows<Prefetch>(s, b, lo, hi, put);
  if constexpr (Prefetch) EntryForces::stream_fence();
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
    Vec3* const force = p.f.data();
    Vec3* const torque = p.torque.data();
    auto add = [force, torque](int l, std::size_t i, std::size_t j, std::uint32_t, const SphereContactBatch& b) {
      const Vec3 f(b.fx[l], b.fy[l], b.fz[l]);
      force[i] += f;
      force[j] -= f;
      torque[i] += Vec3(b.tix[l], b.tiy[l], b.tiz[l]);
      torque[j] += Vec3(b.tjx[l], b.tjy[l], b.tjz[l]);
    };
    if (p.size() >= kPrefetchFrom)
      lanes_rows<true>(s, batch, 0, rows, add);
    else
      lanes_rows<false>(s, batch, 0, rows, add);
  } else {
    e.resize_compact<true>(nl.partner.size());
    const auto n_rows = static_cast<std::ptrdiff_t>(rows);
    constexpr std::ptrdiff_t chunk = 256;
    const bool prefetch = p.size() >= kPrefetchFrom;
#pragma omp parallel
    {
      SphereContactBatch b;
#pragma omp for schedule(dynamic, 1)
      for (std::ptrdiff_t r0 = 0; r0 < n_rows; r0 += chunk) {
        const auto lo = static_cast<std::size_t>(r0), hi = static_cast<std::size_t>(std::min(r0 + chunk, n_rows));
        if (prefetch)
          deferred_rows<true>(s, b, e, lo, hi);
        else
          deferred_rows<false>(s, b, e, lo, hi);
      }
    }
    gather_entry_forces<true>(p, nl, e, prefetch);
    if (s.stress_probe) probe_entries<true>(*s.stress_probe, p, nl, e);
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
