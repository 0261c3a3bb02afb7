// The sphere lanes' list passes with AVX-512F: see sphere_lanes_screen.hpp.
// Compiled with -mavx512f and no FMA contraction (sim/CMakeLists.txt); chosen
// at run time by sphere_lanes.cpp.
#if !defined(__AVX512F__)
#error "sphere_lanes_screen_avx512.cpp must be compiled with -mavx512f"
#endif
// GCC 12 warns of its own _mm512_undefined_* inside the cast intrinsics
// (GCC bug 105593, fixed in GCC 13): not a value of ours.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <immintrin.h>

#include <cstring>

#include "sim/laws/avx512_index.hpp"
#include "sim/laws/sphere_lanes_screen.hpp"

namespace grains::sim::isa_avx512 {

namespace {

using B = SphereContactBatch;
static_assert(B::kPad == 8 && B::kRoom >= B::kSize + 8, "a pass stores eight lanes from any lane below kSize");

using avx512_index::gather;
using avx512_index::load32;
using avx512_index::times3;
using avx512_index::widen;
// Stores the lanes of v that m selects, packed, at p (eight lanes written).
inline void pack(double* p, __mmask8 m, __m512d v) { _mm512_storeu_pd(p, _mm512_maskz_compress_pd(m, v)); }
inline void pack(std::uint32_t* p, __mmask8 m, __m512i v16) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(p),
                      _mm512_castsi512_si256(_mm512_maskz_compress_epi32(static_cast<__mmask16>(m), v16)));
}

}  // namespace

// The first pass runs over the list's entries eight at a time whatever rows
// they belong to (a row holds about four entries in a dense bed: a group per
// row would leave half its lanes empty and branch on every row's length).
// Each window of kWindow entries first gets the row of every entry, one
// eight-lane store per row (a longer row: one per eight entries; an empty
// row's store is overwritten by the next row's, which starts at the same
// entry), so that no branch depends on a row's length.
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
  const __m512d reach = _mm512_set1_pd(in.reach);
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 0, 0, 0, 0, 0, 0, 0, 0);
  const std::size_t entries = in.entries;
  const std::uint32_t last = row_start[row_end];
  std::size_t i = i_io;  // a row at or before the row of entry k
  std::uint32_t k = k_io > row_start[i] ? k_io : row_start[i];
  alignas(64) std::uint32_t row_in_window[kWindow + 8];
  while (k < last) {
    const std::uint32_t window_end = last - k > kWindow ? k + kWindow : last;
    std::size_t r = i;
    for (; r < row_end; ++r) {
      std::uint32_t e0 = row_start[r];
      if (e0 >= window_end) break;
      e0 = e0 > k ? e0 : k;
      const std::uint32_t e1 = row_start[r + 1] < window_end ? row_start[r + 1] : window_end;
      const __m256i rv = _mm256_set1_epi32(static_cast<int>(r));
      do {
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(row_in_window + (e0 - k)), rv);
        e0 += 8;
      } while (e0 < e1);
    }
    for (std::uint32_t q = k; q < window_end;) {
      const std::uint32_t count = window_end - q < 8 ? window_end - q : 8;
      const __mmask8 live = static_cast<__mmask8>((1u << count) - 1);
      const __m512i row32 = load32(row_in_window + (q - k), live), j32 = load32(partner + q, live);
      const __m512i row = widen(row32), j = widen(j32);
      const __m512i i3 = times3(row), j3 = times3(j);
      if (prefetch) {
        // The partners 16 entries ahead (position, radius), and this group's
        // fields for the second pass and the sums (every entry: a test of
        // touch would be mispredicted).
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
      const __m512d dx = _mm512_sub_pd(gather(x, i3, live), gather(x, j3, live));
      const __m512d dy = _mm512_sub_pd(gather(x + 1, i3, live), gather(x + 1, j3, live));
      const __m512d dz = _mm512_sub_pd(gather(x + 2, i3, live), gather(x + 2, j3, live));
      const __m512d ri = gather(radius, row, live), rj = gather(radius, j, live);
      const __m512d d2 =
          _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
      const __m512d rc = _mm512_add_pd(_mm512_add_pd(ri, rj), reach);
      const __mmask8 touch = _mm512_mask_cmp_pd_mask(live, d2, _mm512_mul_pd(rc, rc), _CMP_NGE_UQ);
      // may_touch: the bytes that change are written one by one (in a bed
      // few change from step to step); a pair that came apart loses its spring.
      std::uint64_t old_bytes = 0;
      if (q + 8 <= entries)
        std::memcpy(&old_bytes, may_touch + q, 8);
      else
        for (std::uint32_t e = 0; e < count; ++e) old_bytes |= std::uint64_t{may_touch[q + e]} << (8 * e);
      const __mmask8 was = _mm512_mask_test_epi64_mask(
          live, _mm512_maskz_cvtepu8_epi64(0xff, _mm_cvtsi64_si128(static_cast<long long>(old_bytes))),
          _mm512_set1_epi64(0xff));
      for (unsigned changed = static_cast<unsigned>(was ^ touch); changed != 0; changed &= changed - 1) {
        const unsigned e = static_cast<unsigned>(__builtin_ctz(changed));
        const bool t = (touch >> e) & 1u;
        if (!t) std::memset(history + static_cast<std::size_t>(q + e) * 3, 0, 3 * sizeof(double));
        may_touch[q + e] = t;
      }
      // The touching entries into lanes n, n+1, ...
      pack(b.dx + n, touch, dx), pack(b.dy + n, touch, dy), pack(b.dz + n, touch, dz), pack(b.d2 + n, touch, d2);
      pack(b.ri + n, touch, ri), pack(b.rj + n, touch, rj);
      pack(row_of + n, touch, row32);
      pack(entry_of + n, touch, _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(q)), iota));
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

}  // namespace grains::sim::isa_avx512
