#pragma once
// Index helpers of the AVX2 sphere lanes (sphere_lanes_screen_avx2.cpp, the
// gathered kernel of sphere_lanes.inc in sphere_lanes_avx2.cpp): four lanes
// of 64-bit indices. Include only from units compiled with -mavx2: these
// inline functions must never be compiled for the baseline.
#if !defined(__AVX2__)
#error "avx2_index.hpp is for units compiled with -mavx2"
#endif
#include <immintrin.h>

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

}  // namespace grains::sim::avx2_index
