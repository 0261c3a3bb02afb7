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
  // A full group by loads and a transpose (avx512_index::load3), a group
  // cut short at the end of the rows by gathers.
  static void gather3(const double* base, const std::uint32_t* idx, std::uint32_t count, I64 index3, Live on, D& a,
                      D& b, D& c) {
    if (count == kLanes) return avx512_index::load3(base, idx, a, b, c);
    a = avx512_index::gather(base, index3, on), b = avx512_index::gather(base + 1, index3, on),
    c = avx512_index::gather(base + 2, index3, on);
  }
  // A group's rows are nondecreasing; when they span fewer than 8 rows
  // (a row holds about four entries), their x and radius are 24 and 8
  // consecutive doubles: loaded whole (masked at the end of the rows) and
  // permuted into the lanes, instead of gathered (4 gathers, the slowest
  // instructions of the pass on the Zen 5 VM of bench/RESULTS.md).
  static void row_fields(const double* x, const double* radius, const std::uint32_t* rows, std::uint32_t count,
                         I64 row, I64 row3, Live on, std::size_t row_end, D& a, D& b, D& c, D& r) {
    const std::uint32_t r0 = rows[0];
    if (rows[count - 1] - r0 >= 8) {
      gather3(x, rows, count, row3, on, a, b, c);
      r = gather1(radius, rows, count, row, on);
      return;
    }
    const std::size_t have = row_end - r0 < 8 ? row_end - r0 : 8;  // rows from r0 that exist
    const __m512i rel = _mm512_sub_epi64(row, _mm512_set1_epi64(static_cast<long long>(r0)));
    avx512_index::rows3(x, r0, have, rel, on, a, b, c);
    r = avx512_index::rows1(radius, r0, have, rel, on);
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
