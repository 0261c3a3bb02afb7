// The sphere lanes' first list pass with AVX2, four entries per instruction:
// the form of sphere_lanes_screen_avx512.cpp for processors without
// AVX-512F (see sphere_lanes_screen.hpp). AVX2 has no compress: the
// touching lanes are packed by a permutation from a table of the sixteen
// four-lane masks. Compiled with -mavx2 and no FMA contraction
// (sim/CMakeLists.txt); chosen at run time by sphere_lanes.cpp.
#if !defined(__AVX2__)
#error "sphere_lanes_screen_avx2.cpp must be compiled with -mavx2"
#endif
#include <immintrin.h>

#include <cstring>

#include "sim/laws/avx2_index.hpp"
#include "sim/laws/sphere_lanes_screen.hpp"

namespace grains::sim::isa_avx {

namespace {

using B = SphereContactBatch;
static_assert(B::kPad >= 4 && B::kRoom >= B::kSize + 4, "a pass stores four lanes from any lane below kSize");

using avx2_index::gather;
using avx2_index::lane_mask;
using avx2_index::load32;
using avx2_index::times3;
using avx2_index::widen;

// For each mask of four lanes, the 32-bit lanes that bring its set lanes to
// the front: of doubles (two 32-bit halves each) and of 32-bit indices.
struct PackTables {
  alignas(32) std::int32_t doubles[16][8];
  alignas(32) std::int32_t indices[16][8];
};
constexpr PackTables make_pack_tables() {
  PackTables t{};
  for (int m = 0; m < 16; ++m) {
    int k = 0;
    for (int l = 0; l < 4; ++l)
      if (m >> l & 1) {
        t.doubles[m][2 * k] = 2 * l, t.doubles[m][2 * k + 1] = 2 * l + 1;
        t.indices[m][k] = l;
        ++k;
      }
  }
  return t;
}
constexpr PackTables kPackTables = make_pack_tables();

// Stores the lanes of v that m selects, packed, at p (four lanes written).
inline void pack(double* p, unsigned m, __m256d v) {
  const __m256i perm = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackTables.doubles[m]));
  _mm256_storeu_pd(p, _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(v), perm)));
}
inline void pack(std::uint32_t* p, unsigned m, __m128i v) {
  const __m256i perm = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackTables.indices[m]));
  const __m256i packed = _mm256_permutevar8x32_epi32(_mm256_castsi128_si256(v), perm);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm256_castsi256_si128(packed));
}

}  // namespace

// As the AVX-512 pass: the list's entries four at a time whatever rows they
// belong to, each window of kWindow entries first given the row of every
// entry by one four-lane store per row (a longer row: one per four
// entries), so that no branch depends on a row's length.
int screen_rows(const SphereScreenFields& in, SphereContactBatch& b, int n, std::size_t& i_io, std::uint32_t& k_io,
                std::size_t row_end, bool prefetch) {
  constexpr std::uint32_t kWindow = 64;
  const std::uint32_t* const row_start = in.row_start;
  const std::uint32_t* const partner = in.partner;
  std::uint8_t* const may_touch = in.may_touch;
  double* const history = in.history;
  const double* const x = in.x;
  const double* const radius = in.radius;
  std::uint32_t* const row_of = in.row_of;
  std::uint32_t* const entry_of = in.entry_of;
  std::uint32_t* const partner_of = in.partner_of;
  const __m256d reach = _mm256_set1_pd(in.reach);
  const __m128i iota = _mm_setr_epi32(0, 1, 2, 3);
  const std::size_t entries = in.entries;
  const std::uint32_t last = row_start[row_end];
  std::size_t i = i_io;  // a row at or before the row of entry k
  std::uint32_t k = k_io > row_start[i] ? k_io : row_start[i];
  alignas(32) std::uint32_t row_in_window[kWindow + 4];
  while (k < last) {
    const std::uint32_t window_end = last - k > kWindow ? k + kWindow : last;
    std::size_t r = i;
    for (; r < row_end; ++r) {
      std::uint32_t e0 = row_start[r];
      if (e0 >= window_end) break;
      e0 = e0 > k ? e0 : k;
      const std::uint32_t e1 = row_start[r + 1] < window_end ? row_start[r + 1] : window_end;
      const __m128i rv = _mm_set1_epi32(static_cast<int>(r));
      do {
        _mm_storeu_si128(reinterpret_cast<__m128i*>(row_in_window + (e0 - k)), rv);
        e0 += 4;
      } while (e0 < e1);
    }
    for (std::uint32_t q = k; q < window_end;) {
      const std::uint32_t count = window_end - q < 4 ? window_end - q : 4;
      const unsigned live = (1u << count) - 1;
      const __m256d on = lane_mask(live);
      const __m128i row32 = load32(row_in_window + (q - k), live), j32 = load32(partner + q, live);
      const __m256i row = widen(row32), j = widen(j32);
      const __m256i i3 = times3(row), j3 = times3(j);
      if (prefetch) {
        // (As the AVX-512 pass: the partners 16 entries ahead, and this
        // group's fields for the kernel and the sums.)
        for (std::uint32_t e = q + 16; e < q + 16 + count && e < entries; ++e) {
          __builtin_prefetch(x + 3 * static_cast<std::size_t>(partner[e]));
          __builtin_prefetch(radius + partner[e]);
        }
        for (std::uint32_t e = 0; e < count; ++e) {
          const std::size_t pj = partner[q + e];
          __builtin_prefetch(in.v + 3 * pj);
          __builtin_prefetch(in.omega + 3 * pj);
          __builtin_prefetch(in.mass + pj);
          __builtin_prefetch(in.f + 3 * pj, 1);
          __builtin_prefetch(in.torque + 3 * pj, 1);
        }
      }
      const __m256d dx = _mm256_sub_pd(gather(x, i3, on), gather(x, j3, on));
      const __m256d dy = _mm256_sub_pd(gather(x + 1, i3, on), gather(x + 1, j3, on));
      const __m256d dz = _mm256_sub_pd(gather(x + 2, i3, on), gather(x + 2, j3, on));
      const __m256d ri = gather(radius, row, on), rj = gather(radius, j, on);
      const __m256d d2 =
          _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
      const __m256d rc = _mm256_add_pd(_mm256_add_pd(ri, rj), reach);
      const unsigned touch =
          static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(d2, _mm256_mul_pd(rc, rc), _CMP_NGE_UQ))) & live;
      // may_touch: the bytes that change written one by one; a pair that
      // came apart loses its spring.
      std::uint32_t old_bytes = 0;
      if (q + 4 <= entries)
        std::memcpy(&old_bytes, may_touch + q, 4);
      else
        for (std::uint32_t e = 0; e < count; ++e) old_bytes |= std::uint32_t{may_touch[q + e]} << (8 * e);
      const unsigned was = static_cast<unsigned>((old_bytes & 0xffu) != 0) |
                           static_cast<unsigned>((old_bytes & 0xff00u) != 0) << 1 |
                           static_cast<unsigned>((old_bytes & 0xff0000u) != 0) << 2 |
                           static_cast<unsigned>((old_bytes & 0xff000000u) != 0) << 3;
      for (unsigned changed = (was & live) ^ touch; changed != 0; changed &= changed - 1) {
        const unsigned e = static_cast<unsigned>(__builtin_ctz(changed));
        const bool t = (touch >> e) & 1u;
        if (!t) std::memset(history + static_cast<std::size_t>(q + e) * 3, 0, 3 * sizeof(double));
        may_touch[q + e] = t;
      }
      // The touching entries into lanes n, n+1, ...
      pack(b.dx + n, touch, dx), pack(b.dy + n, touch, dy), pack(b.dz + n, touch, dz), pack(b.d2 + n, touch, d2);
      pack(b.ri + n, touch, ri), pack(b.rj + n, touch, rj);
      pack(row_of + n, touch, row32);
      pack(entry_of + n, touch, _mm_add_epi32(_mm_set1_epi32(static_cast<int>(q)), iota));
      pack(partner_of + n, touch, j32);
      n += __builtin_popcount(touch);
      q += count;
      if (n >= B::kSize) {
        k_io = q;
        i_io = q < window_end ? row_in_window[q - k] : r - 1;
        return n;
      }
    }
    k = window_end;
    i = r - 1;
  }
  i_io = row_end, k_io = last;
  return n;
}

}  // namespace grains::sim::isa_avx
