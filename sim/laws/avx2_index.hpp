#pragma once
// Index helpers of the AVX2 sphere lanes (sphere_lanes_screen_avx2.cpp, the
// gathered kernel of sphere_lanes.inc in sphere_lanes_avx2.cpp): four lanes
// of 64-bit indices. Include only from units compiled with -mavx2: these
// inline functions must never be compiled for the baseline.
#if !defined(__AVX2__)
#error "avx2_index.hpp is for units compiled with -mavx2"
#endif
#include <immintrin.h>

#include <cstddef>
#include <cstdint>

namespace grains::sim::avx2_index {

/// Four 32-bit indices at p (lanes past m, a mask of four bits, read nothing and are zero).
inline __m128i load32(const std::uint32_t* p, unsigned m) {
  const __m128i bit = _mm_setr_epi32(1, 2, 4, 8);
  const __m128i on = _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(static_cast<int>(m)), bit), bit);
  return _mm_maskload_epi32(reinterpret_cast<const int*>(p), on);
}
/// Four 32-bit indices widened to 64 bits.
inline __m256i widen(__m128i v32) { return _mm256_cvtepu32_epi64(v32); }
/// Four 32-bit indices at p, all valid, widened to 64 bits.
inline __m256i load_wide(const std::uint32_t* p) { return widen(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p))); }
inline __m256i times3(__m256i i) { return _mm256_add_epi64(_mm256_slli_epi64(i, 1), i); }
/// The lanes of a four-bit mask as a mask of doubles (all bits set where on).
inline __m256d lane_mask(unsigned m) {
  const __m256i bit = _mm256_setr_epi64x(1, 2, 4, 8);
  return _mm256_castsi256_pd(
      _mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x(static_cast<long long>(m)), bit), bit));
}
/// base[index] in every lane.
inline __m256d gather(const double* base, __m256i index) { return _mm256_i64gather_pd(base, index, 8); }
/// base[index] in the lanes `on` selects (lane_mask), zero in the others (not read).
inline __m256d gather(const double* base, __m256i index, __m256d on) {
  return _mm256_mask_i64gather_pd(_mm256_setzero_pd(), base, index, on, 8);
}

/// Three doubles per item (a Vec3 array, or a spring per list entry): the
/// components c = 0, 1, 2 of items i0 ... i3 into a, b, c, the values that
/// gathers at base + c with indices 3 i would give, by four loads of three
/// doubles (the fourth not read) and a transpose. Cheaper than three
/// gathers where gathers are slow: on Zen 3 the 10^4 bed's pair stage took
/// 3.4 s with these against 5.4 s with gathers (bench/RESULTS.md, 2026-12-02).
inline void load3(const double* base, std::size_t i0, std::size_t i1, std::size_t i2, std::size_t i3, __m256d& a,
                  __m256d& b, __m256d& c) {
  const __m256i three = _mm256_setr_epi64x(-1, -1, -1, 0);
  const __m256d r0 = _mm256_maskload_pd(base + 3 * i0, three), r1 = _mm256_maskload_pd(base + 3 * i1, three);
  const __m256d r2 = _mm256_maskload_pd(base + 3 * i2, three), r3 = _mm256_maskload_pd(base + 3 * i3, three);
  const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);  // x0 x1 z0 z1, y0 y1 0 0
  const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
  a = _mm256_permute2f128_pd(t0, t2, 0x20);
  b = _mm256_permute2f128_pd(t1, t3, 0x20);
  c = _mm256_permute2f128_pd(t0, t2, 0x31);
}
/// The same for the four items idx[0 ... 3].
inline void load3(const double* base, const std::uint32_t* idx, __m256d& a, __m256d& b, __m256d& c) {
  load3(base, idx[0], idx[1], idx[2], idx[3], a, b, c);
}

}  // namespace grains::sim::avx2_index
