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

#include <cstdint>
#include <cstring>

#include "sim/laws/avx512_index.hpp"
#include "sim/laws/sphere_lanes_screen.hpp"

namespace grains::sim::isa_avx512 {

namespace {

// What the first pass (sphere_lanes_screen.inc) does with AVX-512F: eight
// lanes, masks for the lanes, compress for the packing.
struct Ops {
  static constexpr std::uint32_t kLanes = 8;
  using D = __m512d;
  using I32 = __m512i;  // eight 32-bit indices in the low half
  using I64 = __m512i;
  using Live = __mmask8;
  static Live live(unsigned m) { return static_cast<__mmask8>(m); }
  static I32 load32(const std::uint32_t* p, unsigned m) { return avx512_index::load32(p, static_cast<__mmask8>(m)); }
  static I64 widen(I32 v) { return avx512_index::widen(v); }
  static I64 times3(I64 v) { return avx512_index::times3(v); }
  static D gather1(const double* base, const std::uint32_t*, std::uint32_t, I64 index, Live on) {
    return avx512_index::gather(base, index, on);
  }
  static void gather3(const double* base, const std::uint32_t*, std::uint32_t, I64 index3, Live on, D& a, D& b, D& c) {
    a = avx512_index::gather(base, index3, on), b = avx512_index::gather(base + 1, index3, on),
    c = avx512_index::gather(base + 2, index3, on);
  }
  static D set1(double a) { return _mm512_set1_pd(a); }
  static D add(D a, D c) { return _mm512_add_pd(a, c); }
  static D sub(D a, D c) { return _mm512_sub_pd(a, c); }
  static D mul(D a, D c) { return _mm512_mul_pd(a, c); }
  static unsigned touching(D d2, D rc, unsigned m) {
    return _mm512_mask_cmp_pd_mask(static_cast<__mmask8>(m), d2, _mm512_mul_pd(rc, rc), _CMP_NGE_UQ);
  }
  static unsigned was(std::uint64_t bytes, unsigned m) {
    return _mm512_mask_test_epi64_mask(static_cast<__mmask8>(m),
                                       _mm512_maskz_cvtepu8_epi64(0xff, _mm_cvtsi64_si128(static_cast<long long>(bytes))),
                                       _mm512_set1_epi64(0xff));
  }
  static constexpr std::uint32_t kRowStore = 8;
  static void store_rows(std::uint32_t* p, std::uint32_t r) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), _mm256_set1_epi32(static_cast<int>(r)));
  }
  static I32 iota_from(std::uint32_t q) {
    return _mm512_add_epi32(_mm512_set1_epi32(static_cast<int>(q)),
                            _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 0, 0, 0, 0, 0, 0, 0, 0));
  }
  static void pack(double* p, unsigned m, D v) {
    _mm512_storeu_pd(p, _mm512_maskz_compress_pd(static_cast<__mmask8>(m), v));
  }
  static void pack(std::uint32_t* p, unsigned m, I32 v16) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p),
                        _mm512_castsi512_si256(_mm512_maskz_compress_epi32(static_cast<__mmask16>(m), v16)));
  }
};

}  // namespace

#include "sim/laws/sphere_lanes_screen.inc"

}  // namespace grains::sim::isa_avx512
