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

#include <cstdint>
#include <cstring>

#include "sim/laws/avx2_index.hpp"
#include "sim/laws/sphere_lanes_screen.hpp"

namespace grains::sim::isa_avx {

namespace {

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

// What the first pass (sphere_lanes_screen.inc) does with AVX2: four lanes,
// a double mask for the gathers, a permutation for the packing.
struct Ops {
  static constexpr std::uint32_t kLanes = 4;
  using D = __m256d;
  using I32 = __m128i;
  using I64 = __m256i;
  using Live = __m256d;
  static Live live(unsigned m) { return avx2_index::lane_mask(m); }
  static I32 load32(const std::uint32_t* p, unsigned m) { return avx2_index::load32(p, m); }
  static I64 widen(I32 v) { return avx2_index::widen(v); }
  static I64 times3(I64 v) { return avx2_index::times3(v); }
  // Four loads where the processor's gathers are slow (Zen 3); a lane past
  // count repeats lane 0's item.
  static D gather1(const double* base, const std::uint32_t* idx, std::uint32_t count, I64, Live) {
    const std::uint32_t i0 = idx[0];
    return _mm256_setr_pd(base[i0], base[count > 1 ? idx[1] : i0], base[count > 2 ? idx[2] : i0],
                          base[count > 3 ? idx[3] : i0]);
  }
  static void gather3(const double* base, const std::uint32_t* idx, std::uint32_t count, I64, Live, D& a, D& b, D& c) {
    const std::uint32_t i0 = idx[0];
    avx2_index::load3(base, i0, count > 1 ? idx[1] : i0, count > 2 ? idx[2] : i0, count > 3 ? idx[3] : i0, a, b, c);
  }
  static void row_fields(const double* x, const double* radius, const std::uint32_t* rows, std::uint32_t count, I64 row,
                         I64 row3, Live on, std::size_t, D& a, D& b, D& c, D& r) {
    gather3(x, rows, count, row3, on, a, b, c);
    r = gather1(radius, rows, count, row, on);
  }
  static D set1(double a) { return _mm256_set1_pd(a); }
  static D add(D a, D c) { return _mm256_add_pd(a, c); }
  static D sub(D a, D c) { return _mm256_sub_pd(a, c); }
  static D mul(D a, D c) { return _mm256_mul_pd(a, c); }
  static unsigned touching(D d2, D rc, unsigned m) {
    return static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(d2, _mm256_mul_pd(rc, rc), _CMP_NGE_UQ))) & m;
  }
  static unsigned was(std::uint64_t bytes, unsigned m) {
    return (static_cast<unsigned>((bytes & 0xffu) != 0) | static_cast<unsigned>((bytes & 0xff00u) != 0) << 1 |
            static_cast<unsigned>((bytes & 0xff0000u) != 0) << 2 |
            static_cast<unsigned>((bytes & 0xff000000u) != 0) << 3) &
           m;
  }
  // Eight slots per store: a row of up to eight entries (nearly all) takes one.
  static constexpr std::uint32_t kRowStore = 8;
  static void store_rows(std::uint32_t* p, std::uint32_t r) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), _mm256_set1_epi32(static_cast<int>(r)));
  }
  static I32 iota_from(std::uint32_t q) {
    return _mm_add_epi32(_mm_set1_epi32(static_cast<int>(q)), _mm_setr_epi32(0, 1, 2, 3));
  }
  // The lanes of v that m selects, packed, at p (four lanes written).
  static void pack(double* p, unsigned m, D v) {
    const __m256i perm = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackTables.doubles[m]));
    _mm256_storeu_pd(p, _mm256_castps_pd(_mm256_permutevar8x32_ps(_mm256_castpd_ps(v), perm)));
  }
  static void pack(std::uint32_t* p, unsigned m, I32 v) {
    const __m256i perm = _mm256_load_si256(reinterpret_cast<const __m256i*>(kPackTables.indices[m]));
    const __m256i packed = _mm256_permutevar8x32_epi32(_mm256_castsi128_si256(v), perm);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(p), _mm256_castsi256_si128(packed));
  }
};

}  // namespace

#include "sim/laws/sphere_lanes_screen.inc"

}  // namespace grains::sim::isa_avx
