#pragma once
// Index helpers of the AVX-512 sphere lanes (sphere_lanes_screen_avx512.cpp,
// the gathered kernel of sphere_lanes.inc in sphere_lanes_avx512.cpp).
// Include only from units compiled with -mavx512f: these inline functions
// must never be compiled for the baseline.
#if !defined(__AVX512F__)
#error "avx512_index.hpp is for units compiled with -mavx512f"
#endif
#include <immintrin.h>

#include <cstdint>

namespace grains::sim::avx512_index {

// (The masked forms throughout: GCC 12 warns, -Wmaybe-uninitialized, on the
// plain ones' _mm512_undefined_*, GCC bug 105593; widen's cast still makes
// it warn, so a unit that calls widen silences that warning.)

/// Eight 32-bit indices at p (lanes past m read nothing and are zero; lanes
/// 8-15 zero).
inline __m512i load32(const std::uint32_t* p, __mmask8 m) {
  return _mm512_maskz_loadu_epi32(static_cast<__mmask16>(m), p);
}
/// The low eight 32-bit lanes widened to 64 bits.
inline __m512i widen(__m512i v32) { return _mm512_maskz_cvtepu32_epi64(0xff, _mm512_castsi512_si256(v32)); }
/// Eight 32-bit indices at p, all valid, widened to 64 bits.
inline __m512i load_wide(const std::uint32_t* p) {
  return _mm512_maskz_cvtepu32_epi64(0xff, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)));
}
inline __m512i times3(__m512i i) { return _mm512_add_epi64(_mm512_maskz_slli_epi64(0xff, i, 1), i); }
/// base[index] in the lanes m selects, zero in the others (not read).
inline __m512d gather(const double* base, __m512i index, __mmask8 m = 0xff) {
  return _mm512_mask_i64gather_pd(_mm512_setzero_pd(), m, index, base, 8);
}

}  // namespace grains::sim::avx512_index
