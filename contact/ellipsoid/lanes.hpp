#pragma once
// A small fixed group of doubles computed in lockstep ("lanes"), for the
// contact kernels that are written once for a scalar type T and run either on
// one pair (T = double) or on kLanes independent pairs at a time (T = Lanes).
//
// Why: one ellipsoid pair's PW85 solve and contact geometry is a chain of
// dependent divisions and square roots (~150 ns, mostly waiting on them).
// kLanes pairs in lockstep give the processor independent chains to overlap,
// and every operator below is packed SIMD (two doubles per SSE2 instruction
// in the baseline copy, four per AVX instruction in the AVX2 copy that
// pw85_lanes.cpp chooses at run time, or in a -march=native build). Each
// lane's result is the same arithmetic as the scalar code's.
//
// The generic kernels use only: + - * / with doubles mixed in, comparisons
// giving a mask (bool for double, LaneMask for Lanes), &, select(m, a, b),
// sqrt_(x), sign_(x) (copysign(1, x)), all_of(m), any_of(m), get_lane(x, l),
// set_lane(x, l, v), lane(mask, l) and lane_count<T>.
#include <cmath>
#include <cstdint>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

// Hot kernels are forced inline into their loops (also in contact_geometry.hpp).
#ifndef GRAINS_INLINE
#define GRAINS_INLINE inline __attribute__((always_inline))
#endif

// Everything below is compiled once per instruction set (pw85_lanes.cpp
// baseline, pw85_lanes_avx2.cpp with AVX2; the sphere kernel also with
// AVX-512, sphere_lanes_avx512.cpp), so it lives in a namespace named after
// it: the copies never meet at link time. Eight lanes of AVX-512 only where a
// file asks for them (defining GRAINS_LANES_512_WANTED; a -march=native build keeps four).
#if defined(__AVX512F__) && defined(GRAINS_LANES_512_WANTED)
#define GRAINS_LANES_512 1
#else
#define GRAINS_LANES_512 0
#endif
#if GRAINS_LANES_512
#define GRAINS_LANES_ISA isa_avx512
#elif defined(__AVX__)
#define GRAINS_LANES_ISA isa_avx
#else
#define GRAINS_LANES_ISA isa_base
#endif

namespace grains::contact {
inline namespace GRAINS_LANES_ISA {

// The lanes are held as GCC/Clang vector types of kPack doubles (two with
// SSE2, the x86-64 baseline; four with AVX; eight with AVX-512, where a
// lane group is one instruction of eight), so every operator below is
// kLanes / kPack packed instructions whatever the optimiser decides.
#if GRAINS_LANES_512
inline constexpr int kLanes = 8;
#else
inline constexpr int kLanes = 4;
#endif
#if GRAINS_LANES_512
inline constexpr int kPack = 8;
#elif defined(__AVX__)
inline constexpr int kPack = 4;
#else
inline constexpr int kPack = 2;
#endif
inline constexpr int kPacks = kLanes / kPack;
typedef double PackD __attribute__((vector_size(8 * kPack)));
typedef std::int64_t PackM __attribute__((vector_size(8 * kPack)));

struct LaneMask {
  PackM p[kPacks];  // all bits set (true) or clear (false), per lane
};

struct Lanes {
  PackD p[kPacks];
  Lanes() = default;
  Lanes(double s) {  // NOLINT: broadcast, so that mixed expressions read as scalar code
    for (int i = 0; i < kPacks; ++i) p[i] = s - PackD{};
  }
};

// a op b pack by pack, with a result of type R (Lanes for arithmetic,
// LaneMask for comparisons); a double operand is broadcast.
#define GRAINS_LANES_OP(R, op)                                                    \
  GRAINS_INLINE R operator op(const Lanes& a, const Lanes& b) {                   \
    R r;                                                                          \
    for (int i = 0; i < kPacks; ++i) r.p[i] = a.p[i] op b.p[i];                   \
    return r;                                                                     \
  }                                                                               \
  GRAINS_INLINE R operator op(double a, const Lanes& b) { return Lanes(a) op b; } \
  GRAINS_INLINE R operator op(const Lanes& a, double b) { return a op Lanes(b); }
GRAINS_LANES_OP(Lanes, +)
GRAINS_LANES_OP(Lanes, -)
GRAINS_LANES_OP(Lanes, *)
GRAINS_LANES_OP(Lanes, /)
GRAINS_LANES_OP(LaneMask, <)
GRAINS_LANES_OP(LaneMask, >)
GRAINS_LANES_OP(LaneMask, !=)
#undef GRAINS_LANES_OP

GRAINS_INLINE Lanes operator-(const Lanes& a) {
  Lanes r;
  for (int i = 0; i < kPacks; ++i) r.p[i] = -a.p[i];
  return r;
}

GRAINS_INLINE LaneMask operator&(const LaneMask& a, const LaneMask& b) {
  LaneMask m;
  for (int i = 0; i < kPacks; ++i) m.p[i] = a.p[i] & b.p[i];
  return m;
}

// m ? a : b per lane, by bit masks.
GRAINS_INLINE Lanes select(const LaneMask& m, const Lanes& a, const Lanes& b) {
  Lanes r;
  for (int i = 0; i < kPacks; ++i) r.p[i] = (PackD)((m.p[i] & (PackM)a.p[i]) | (~m.p[i] & (PackM)b.p[i]));
  return r;
}
GRAINS_INLINE Lanes sqrt_(const Lanes& a) {
  Lanes r;
  for (int i = 0; i < kPacks; ++i)
#if GRAINS_LANES_512
    r.p[i] = (PackD)_mm512_maskz_sqrt_pd((__mmask8)-1, (__m512d)a.p[i]);  // (maskz: GCC 12 warns on _mm512_sqrt_pd)
#elif defined(__AVX__)
    r.p[i] = (PackD)_mm256_sqrt_pd((__m256d)a.p[i]);
#elif defined(__SSE2__)
    r.p[i] = (PackD)_mm_sqrt_pd((__m128d)a.p[i]);
#else
    for (int e = 0; e < kPack; ++e) r.p[i][e] = std::sqrt(a.p[i][e]);
#endif
  return r;
}
// copysign(1, a) per lane: the sign bit of a on 1.0.
GRAINS_INLINE Lanes sign_(const Lanes& a) {
  const PackM sign_bit = (PackM{} + 1) << 63, one = (PackM)(PackD{} + 1.0);
  Lanes r;
  for (int i = 0; i < kPacks; ++i) r.p[i] = (PackD)(((PackM)a.p[i] & sign_bit) | one);
  return r;
}
GRAINS_INLINE bool all_of(const LaneMask& m) {
  for (int i = 0; i < kPacks; ++i)
    for (int e = 0; e < kPack; ++e)
      if (!m.p[i][e]) return false;
  return true;
}
GRAINS_INLINE bool any_of(const LaneMask& m) {
  PackM acc = m.p[0];
  for (int i = 1; i < kPacks; ++i) acc |= m.p[i];
  for (int e = 0; e < kPack; ++e)
    if (acc[e]) return true;
  return false;
}
// Lanes from f(0), ..., f(kLanes - 1), assembled in registers. (Writing
// single lanes into a pack in memory and then reading the pack would stall
// the load on the narrower stores: store-to-load forwarding fails.)
template <class F>
GRAINS_INLINE Lanes gather_lanes(F&& f) {
  Lanes r;
  for (int i = 0; i < kPacks; ++i) {
#if GRAINS_LANES_512
    r.p[i] = PackD{f(8 * i),     f(8 * i + 1), f(8 * i + 2), f(8 * i + 3),
                   f(8 * i + 4), f(8 * i + 5), f(8 * i + 6), f(8 * i + 7)};
#elif defined(__AVX__)
    r.p[i] = PackD{f(4 * i), f(4 * i + 1), f(4 * i + 2), f(4 * i + 3)};
#else
    r.p[i] = PackD{f(2 * i), f(2 * i + 1)};
#endif
  }
  return r;
}

GRAINS_INLINE double get_lane(const Lanes& a, int l) { return a.p[l / kPack][l % kPack]; }
GRAINS_INLINE void set_lane(Lanes& a, int l, double v) { a.p[l / kPack][l % kPack] = v; }
GRAINS_INLINE bool lane(const LaneMask& m, int l) { return m.p[l / kPack][l % kPack] != 0; }

// The scalar side of the same vocabulary.
inline double select(bool m, double a, double b) { return m ? a : b; }
inline double sqrt_(double a) { return std::sqrt(a); }
inline double sign_(double a) { return std::copysign(1.0, a); }
inline bool all_of(bool m) { return m; }
inline bool any_of(bool m) { return m; }
inline double get_lane(double a, int) { return a; }
inline void set_lane(double& a, int, double v) { a = v; }
inline bool lane(bool m, int) { return m; }

template <class T>
inline constexpr int lane_count = 1;
template <>
inline constexpr int lane_count<Lanes> = kLanes;

template <class T>
using MaskOf = decltype(T() < T());

}  // namespace GRAINS_LANES_ISA
}  // namespace grains::contact
