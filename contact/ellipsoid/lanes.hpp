#pragma once
// A small fixed group of doubles computed in lockstep ("lanes"), for the
// contact kernels that are written once for a scalar type T and run either on
// one pair (T = double) or on kLanes independent pairs at a time (T = Lanes).
//
// Why: one ellipsoid pair's PW85 solve and contact geometry is a chain of
// dependent divisions and square roots (~150 ns, mostly waiting on them).
// kLanes pairs in lockstep give the processor independent chains to overlap,
// and every operator below is a loop of constant trip count that the
// compiler turns into packed SIMD instructions (two doubles per SSE2
// instruction in the default build, four with -march=native on AVX2).
// Each lane's result is the same arithmetic as the scalar code's.
//
// The generic kernels use only: + - * / with doubles mixed in, comparisons
// giving a mask (bool for double, LaneMask for Lanes), &, select(m, a, b),
// sqrt_(x), sign_(x) (copysign(1, x)), all_of(m), lane(x, l) and lane_count<T>.
#include <cmath>
#include <cstdint>

namespace grains::contact {

inline constexpr int kLanes = 4;

struct LaneMask {
  std::int64_t v[kLanes];  // all bits set (true) or clear (false), per lane
};

struct Lanes {
  double v[kLanes];
  Lanes() = default;
  Lanes(double s) {  // NOLINT: broadcast, so that mixed expressions read as scalar code
    for (int l = 0; l < kLanes; ++l) v[l] = s;
  }
};

#define GRAINS_LANES_BINARY(op)                                                \
  inline Lanes operator op(const Lanes& a, const Lanes& b) {                   \
    Lanes r;                                                                   \
    for (int l = 0; l < kLanes; ++l) r.v[l] = a.v[l] op b.v[l];                \
    return r;                                                                  \
  }                                                                            \
  inline Lanes operator op(double a, const Lanes& b) { return Lanes(a) op b; } \
  inline Lanes operator op(const Lanes& a, double b) { return a op Lanes(b); } \
  inline Lanes& operator op##=(Lanes& a, const Lanes& b) { return a = a op b; }
GRAINS_LANES_BINARY(+)
GRAINS_LANES_BINARY(-)
GRAINS_LANES_BINARY(*)
GRAINS_LANES_BINARY(/)
#undef GRAINS_LANES_BINARY

inline Lanes operator-(const Lanes& a) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r.v[l] = -a.v[l];
  return r;
}

#define GRAINS_LANES_COMPARE(op)                                                   \
  inline LaneMask operator op(const Lanes& a, const Lanes& b) {                    \
    LaneMask m;                                                                    \
    for (int l = 0; l < kLanes; ++l) m.v[l] = a.v[l] op b.v[l] ? -1 : 0;           \
    return m;                                                                      \
  }                                                                                \
  inline LaneMask operator op(const Lanes& a, double b) { return a op Lanes(b); }
GRAINS_LANES_COMPARE(<)
GRAINS_LANES_COMPARE(>)
GRAINS_LANES_COMPARE(!=)
#undef GRAINS_LANES_COMPARE

inline LaneMask operator&(const LaneMask& a, const LaneMask& b) {
  LaneMask m;
  for (int l = 0; l < kLanes; ++l) m.v[l] = a.v[l] & b.v[l];
  return m;
}

inline Lanes select(const LaneMask& m, const Lanes& a, const Lanes& b) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r.v[l] = m.v[l] ? a.v[l] : b.v[l];
  return r;
}
inline Lanes sqrt_(const Lanes& a) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r.v[l] = std::sqrt(a.v[l]);
  return r;
}
inline Lanes sign_(const Lanes& a) {
  Lanes r;
  for (int l = 0; l < kLanes; ++l) r.v[l] = std::copysign(1.0, a.v[l]);
  return r;
}
inline bool all_of(const LaneMask& m) {
  std::int64_t a = -1;
  for (int l = 0; l < kLanes; ++l) a &= m.v[l];
  return a != 0;
}
inline double& lane(Lanes& a, int l) { return a.v[l]; }
inline double lane(const Lanes& a, int l) { return a.v[l]; }
inline bool lane(const LaneMask& m, int l) { return m.v[l] != 0; }

// The scalar side of the same vocabulary.
inline double select(bool m, double a, double b) { return m ? a : b; }
inline double sqrt_(double a) { return std::sqrt(a); }
inline double sign_(double a) { return std::copysign(1.0, a); }
inline bool all_of(bool m) { return m; }
inline double& lane(double& a, int) { return a; }
inline double lane(const double& a, int) { return a; }
inline bool lane(bool m, int) { return m; }

template <class T>
inline constexpr int lane_count = 1;
template <>
inline constexpr int lane_count<Lanes> = kLanes;

template <class T>
using MaskOf = decltype(T() < T());

}  // namespace grains::contact
