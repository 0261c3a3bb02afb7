// The lockstep Hertz–Mindlin arithmetic (sphere_lanes.inc) compiled with AVX2
// (four lanes per instruction), without FMA contraction so that it gives the
// scalar law's bits; chosen at run time by sphere_lanes.cpp.
#if !defined(__AVX2__)
#error "sphere_lanes_avx2.cpp must be compiled with -mavx2"
#endif
#define GRAINS_LANES_GATHERED 1  // also the kernel that gathers the motion (sphere_lanes_screen.hpp)
#include "sim/laws/sphere_lanes.inc"
