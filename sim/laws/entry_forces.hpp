#pragma once
// The deterministic, thread-parallel way of summing pair forces
// (Scene::deterministic): each list entry's force and torques are computed
// into per-entry slots (rows in parallel, no two threads write the same
// slot), then every owned particle sums its entries in the order of the
// other particle's global id (NeighborList::gather_*). The sum therefore
// does not depend on the thread count, the rank count or the local order
// of particles, and there are no write races.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "sim/neighbor/neighbor_list.hpp"
#include "sim/state/particle_store.hpp"

namespace grains::sim {

/// Per list entry k, what each of its two particles gets, in the layout the
/// gather reads: side 0 (the row particle) holds (f, ti), side 1 (the
/// partner) holds (-f, tj), side s of entry k at element (2k + s) * side
/// size, which is NeighborList::gather_entry's code times the side size.
/// The gather then adds whole sides, with no sign or choice per entry
/// (a + (-f) is a - f to the bit). Without rotation a side is the force
/// alone. An entry not in contact holds zeros.
///
/// The compact layout (the sphere lanes, resize_compact): entry k's sides
/// are record slot[k]'s, records 1, 2, ... holding the entries in contact
/// as they come and record 0 zeros, so that a step writes the records of
/// the contacts and four bytes for every other entry (not the whole array).
/// The gather adds the same values in the same order either way.
struct EntryForces {
  template <bool Rotation>
  static constexpr std::size_t kSide = Rotation ? 6 : 3;
  std::vector<double> v;
  std::vector<std::uint32_t> slot;  // the compact layout: entry -> record
  bool compact = false;

  template <bool Rotation>
  void resize(std::size_t entries) {
    compact = false;
    v.resize(entries * 2 * kSide<Rotation>);
  }
  /// The compact layout for `entries` entries: room for a record each and
  /// the zero record. Every entry's slot must then be written (put or
  /// clear_slots) before the gather.
  template <bool Rotation>
  void resize_compact(std::size_t entries) {
    compact = true;
    v.resize((entries + 1) * 2 * kSide<Rotation>);
    std::fill_n(v.begin(), 2 * kSide<Rotation>, 0.0);
    slot.resize(entries);
  }
  /// Entries [k0, k1) not in contact (until put), in the compact layout.
  void clear_slots(std::size_t k0, std::size_t k1) {
    std::fill(slot.begin() + static_cast<std::ptrdiff_t>(k0), slot.begin() + static_cast<std::ptrdiff_t>(k1), 0u);
  }
  /// Entry k in contact, its sides into record rec (> 0), in the compact layout.
  template <bool Rotation>
  void put(std::uint32_t rec, std::size_t k, const Vec3& f, const Vec3& ti, const Vec3& tj) {
    slot[k] = rec;
    set<Rotation>(rec, f, ti, tj);
  }
  /// put, with the record's stores past the cache (non-temporal): for a bed
  /// whose records leave the cache before the gather reads them, the stores
  /// then do not first read the lines they fill (ordered sums in beds of
  /// 10^5 and 10^6 grains, serial and on 2 ranks: bench/RESULTS.md,
  /// 2026-12-07). The same values.
  /// stream_fence() must follow before any thread reads the records.
  template <bool Rotation>
  void put_stream(std::uint32_t rec, std::size_t k, const Vec3& f, const Vec3& ti, const Vec3& tj) {
#if defined(__SSE2__)
    static_assert(Rotation, "written for the sphere lanes' records (with rotation), the only ones streamed");
    static_assert(__STDCPP_DEFAULT_NEW_ALIGNMENT__ >= 16, "records (12 doubles) on 16-byte boundaries");
    slot[k] = rec;
    double* const q = v.data() + std::size_t{rec} * 2 * kSide<Rotation>;
    // set()'s layout, two doubles at a time (_mm_set_pd(hi, lo)); the lanes
    // test compares the ordered sums it gives with the scalar loop's bitwise.
    _mm_stream_pd(q, _mm_set_pd(f.y(), f.x())), _mm_stream_pd(q + 2, _mm_set_pd(ti.x(), f.z()));
    _mm_stream_pd(q + 4, _mm_set_pd(ti.z(), ti.y())), _mm_stream_pd(q + 6, _mm_set_pd(-f.y(), -f.x()));
    _mm_stream_pd(q + 8, _mm_set_pd(tj.x(), -f.z())), _mm_stream_pd(q + 10, _mm_set_pd(tj.z(), tj.y()));
#else
    put<Rotation>(rec, k, f, ti, tj);
#endif
  }
  /// Orders this thread's put_stream stores before its later ones (and so
  /// before an OpenMP barrier's).
  static void stream_fence() {
#if defined(__SSE2__)
    _mm_sfence();
#endif
  }
  template <bool Rotation>
  void set(std::size_t k, const Vec3& f, const Vec3& ti, const Vec3& tj) {
    double* q = v.data() + k * 2 * kSide<Rotation>;
    q[0] = f.x(), q[1] = f.y(), q[2] = f.z();
    q += 3;
    if constexpr (Rotation) q[0] = ti.x(), q[1] = ti.y(), q[2] = ti.z(), q += 3;
    q[0] = -f.x(), q[1] = -f.y(), q[2] = -f.z();
    if constexpr (Rotation) q[3] = tj.x(), q[4] = tj.y(), q[5] = tj.z();
  }
  /// Entries [k0, k1) not in contact (until set).
  template <bool Rotation>
  void zero(std::size_t k0, std::size_t k1) {
    std::fill(v.begin() + static_cast<std::ptrdiff_t>(k0 * 2 * kSide<Rotation>),
              v.begin() + static_cast<std::ptrdiff_t>(k1 * 2 * kSide<Rotation>), 0.0);
  }
  /// Bytes held (summary.json: ordered_sums_entry_forces).
  double bytes() const {
    return static_cast<double>(v.size() * sizeof(double) + slot.size() * sizeof(std::uint32_t));
  }
  /// The force of entry k on its row particle.
  template <bool Rotation>
  Vec3 force(std::size_t k) const {
    const double* q = v.data() + (compact ? std::size_t{slot[k]} : k) * 2 * kSide<Rotation>;
    return {q[0], q[1], q[2]};
  }
};

namespace detail {
/// The compact layout's gather (see gather_entry_forces). With Prefetch,
/// the slot of the entry kSlotAhead places ahead and the record of the one
/// kRecordAhead ahead (both its cache lines) are prefetched, which reads
/// that entry's slot, prefetched kSlotAhead - kRecordAhead entries before.
template <bool Rotation, bool Prefetch>
inline void gather_compact(ParticleStore& p, const NeighborList& nl, const EntryForces& e) {
  constexpr std::size_t S = EntryForces::kSide<Rotation>;
  constexpr std::size_t kSlotAhead = 256, kRecordAhead = 128;
  const auto n = static_cast<std::ptrdiff_t>(p.n_owned());
  const double* const v = e.v.data();
  const std::uint32_t* const gather_start = nl.gather_start.data();
  const std::uint32_t* const gather_entry = nl.gather_entry.data();
  const std::uint32_t* const slot = e.slot.data();
  [[maybe_unused]] const std::size_t total = gather_start[static_cast<std::size_t>(n)];
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    double a[S] = {};
    for (auto g = gather_start[i]; g < gather_start[i + 1]; ++g) {
      if constexpr (Prefetch) {
        if (g + kSlotAhead < total) __builtin_prefetch(slot + (gather_entry[g + kSlotAhead] >> 1));
        if (g + kRecordAhead < total) {
          const std::uint32_t c = gather_entry[g + kRecordAhead];
          const double* const r = v + (2 * std::size_t{slot[c >> 1]} + (c & 1u)) * S;
          __builtin_prefetch(r);
          __builtin_prefetch(r + S - 1);
        }
      }
      const std::uint32_t code = gather_entry[g];  // 2 k + side
      const double* const q = v + (2 * std::size_t{slot[code >> 1]} + (code & 1u)) * S;
      for (std::size_t c = 0; c < S; ++c) a[c] += q[c];
    }
    p.f[i] += Vec3(a[0], a[1], a[2]);
    if constexpr (Rotation) p.torque[i] += Vec3(a[3], a[4], a[5]);
  }
}
}  // namespace detail

/// Adds each owned particle's entries to its force (and torque), in the
/// list's gather order. `prefetch` (the compact layout only; the caller's
/// choice, by the particle count from which it prefetches its own reads):
/// in a large bed a grain's entries lie in rows up to a layer of cells away
/// and their records far apart in memory, and without prefetches the gather
/// waits on each (bench/RESULTS.md, 2026-12-06: 73-100 ns per grain in a bed
/// of 10^6, about 10 in one of 10^4 that the cache holds).
template <bool Rotation>
inline void gather_entry_forces(ParticleStore& p, const NeighborList& nl, const EntryForces& e,
                                bool prefetch = false) {
  if (e.compact) {
    if (prefetch)
      detail::gather_compact<Rotation, true>(p, nl, e);
    else
      detail::gather_compact<Rotation, false>(p, nl, e);
    return;
  }
  constexpr std::size_t S = EntryForces::kSide<Rotation>;
  const auto n = static_cast<std::ptrdiff_t>(p.n_owned());
  const double* const v = e.v.data();
  const std::uint32_t* const gather_start = nl.gather_start.data();
  const std::uint32_t* const gather_entry = nl.gather_entry.data();
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    double a[S] = {};
    for (auto g = gather_start[i]; g < gather_start[i + 1]; ++g) {
      const double* const q = v + std::size_t{gather_entry[g]} * S;
      for (std::size_t c = 0; c < S; ++c) a[c] += q[c];
    }
    p.f[i] += Vec3(a[0], a[1], a[2]);
    if constexpr (Rotation) p.torque[i] += Vec3(a[3], a[4], a[5]);
  }
}

}  // namespace grains::sim
