#pragma once
// Index helpers of the AVX-512 sphere lanes (sphere_lanes_screen_avx512.cpp,
// the gathered kernel of sphere_lanes.inc in sphere_lanes_avx512.cpp).
// Include only from units compiled with -mavx512f: these inline functions
// must never be compiled for the baseline.
#if !defined(__AVX512F__)
#error "avx512_index.hpp is for units compiled with -mavx512f"
#endif
#include <immintrin.h>

#include <cstddef>
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

/// Three doubles per item (a Vec3 array, or a spring per list entry): the
/// components c = 0, 1, 2 of items idx[0 ... 7] into a, b, c, the values
/// that gathers at base + c with indices 3 idx would give, by eight masked
/// loads of three doubles (two items to a register: the second's read four
/// doubles low, so that they land in lanes 4-6) and a transpose. Cheaper than
/// the three gathers on the Zen 5 VM of bench/RESULTS.md (2026-12-07) where
/// the cache holds the items; in scenes past it the kernel's partners
/// measured faster gathered (sphere_lanes.inc).
inline void load3(const double* base, const std::uint32_t* idx, __m512d& a, __m512d& b, __m512d& c) {
  const auto pair = [base](std::uint32_t lo, std::uint32_t hi) {
    const __m512d l = _mm512_maskz_loadu_pd(0x07, base + 3 * std::size_t{lo});
    // (Lanes 4-6 from item hi's three doubles: the masked-off lanes are not read.)
    const auto at = reinterpret_cast<std::uintptr_t>(base + 3 * static_cast<std::size_t>(hi)) - 4 * sizeof(double);
    return _mm512_mask_loadu_pd(l, 0x70, reinterpret_cast<const void*>(at));
  };
  const __m512d z0 = pair(idx[0], idx[2]), z1 = pair(idx[1], idx[3]);  // x y z 0 of items 0 | 2, 1 | 3
  const __m512d z2 = pair(idx[4], idx[6]), z3 = pair(idx[5], idx[7]);
  const __m512d t0 = _mm512_unpacklo_pd(z0, z1), t1 = _mm512_unpackhi_pd(z0, z1);  // x0 x1 z0 z1 x2 x3 z2 z3, y..
  const __m512d t2 = _mm512_unpacklo_pd(z2, z3), t3 = _mm512_unpackhi_pd(z2, z3);
  a = _mm512_shuffle_f64x2(t0, t2, _MM_SHUFFLE(2, 0, 2, 0));
  b = _mm512_shuffle_f64x2(t1, t3, _MM_SHUFFLE(2, 0, 2, 0));
  c = _mm512_shuffle_f64x2(t0, t2, _MM_SHUFFLE(3, 1, 3, 1));
}

/// Consecutive rows r0 ... r0 + 7 of a three-double field, those of them
/// below r0 + have (the others zero, not read): 24 doubles in 3 registers.
struct Rows3 {
  __m512d x0, x1, x2;
};
inline Rows3 load_rows3(const double* base, std::size_t r0, std::size_t have) {
  const std::uint32_t m = (1u << (3 * have)) - 1;
  const double* p = base + 3 * r0;
  return {_mm512_maskz_loadu_pd(static_cast<__mmask8>(m), p),
          _mm512_maskz_loadu_pd(static_cast<__mmask8>(m >> 8), p + 8),
          _mm512_maskz_loadu_pd(static_cast<__mmask8>(m >> 16), p + 16)};
}
/// Double idx (0 ... 23) of w in the lanes of on, zero in the others.
inline __m512d pick(const Rows3& w, __m512i idx, __mmask8 on) {
  const __mmask8 high = _mm512_mask_cmpge_epi64_mask(on, idx, _mm512_set1_epi64(16));
  const __m512d lo = _mm512_maskz_permutex2var_pd(on, w.x0, idx, w.x1);
  return _mm512_mask_permutexvar_pd(lo, high, idx, w.x2);
}
/// The components of rows r0 + rel (rel < 8 and below have, per lane of on)
/// of a three-double field, as gathers with indices 3 (r0 + rel) would give.
inline void rows3(const double* base, std::size_t r0, std::size_t have, __m512i rel, __mmask8 on, __m512d& a,
                  __m512d& b, __m512d& c) {
  const Rows3 w = load_rows3(base, r0, have);
  const __m512i rel3 = times3(rel);
  a = pick(w, rel3, on);
  b = pick(w, _mm512_add_epi64(rel3, _mm512_set1_epi64(1)), on);
  c = pick(w, _mm512_add_epi64(rel3, _mm512_set1_epi64(2)), on);
}
/// The same for a one-double field.
inline __m512d rows1(const double* base, std::size_t r0, std::size_t have, __m512i rel, __mmask8 on) {
  return _mm512_maskz_permutexvar_pd(on, rel, _mm512_maskz_loadu_pd(static_cast<__mmask8>((1u << have) - 1), base + r0));
}

}  // namespace grains::sim::avx512_index
