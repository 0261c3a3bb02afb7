// The spreading / interpolation arithmetic compiled with AVX2 + FMA
// (CMakeLists.txt sets the flags for this file only, on x86-64); used when
// the CPU has both (spreader.cpp checks at run time).
#include "contact/correlation/spreader_kernels.hpp"

#if GRAINS_SPREAD_AVX2
#define GRAINS_SPREAD_SUFFIX avx2
#include "contact/correlation/spreader_kernels.inc"
#endif
