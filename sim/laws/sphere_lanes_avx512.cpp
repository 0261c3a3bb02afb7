// The lockstep Hertz–Mindlin arithmetic (sphere_lanes.inc) compiled with
// AVX-512 (eight lanes per instruction: half the square-root and division
// instructions of the AVX2 copy per contact), without FMA contraction so that
// it gives the scalar law's bits; chosen at run time by sphere_lanes.cpp.
#if !defined(__AVX512F__)
#error "sphere_lanes_avx512.cpp must be compiled with -mavx512f"
#endif
// GCC 12 warns of its own _mm512_undefined_* inside the unpack and shuffle
// intrinsics of avx512_index::load3 (GCC bug 105593, fixed in GCC 13).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#define GRAINS_LANES_512_WANTED 1
#define GRAINS_LANES_GATHERED 1  // also the kernel that gathers the motion (sphere_lanes_screen.hpp)
#include "sim/laws/sphere_lanes.inc"
