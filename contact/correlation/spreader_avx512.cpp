// The spreading / interpolation arithmetic compiled with AVX-512 (F, VL, DQ)
// + FMA (CMakeLists.txt sets the flags for this file only, on x86-64); used
// when the CPU has them (spreader.cpp checks at run time). Subgrid-row
// updates are padded to whole 8-double vectors (W = 7 complex values: two
// zmm registers instead of three ymm and an xmm).
#include "contact/correlation/spreader_kernels.hpp"

#if GRAINS_SPREAD_AVX2
#define GRAINS_SPREAD_SUFFIX avx512
#define GRAINS_SPREAD_LANES 8
#include "contact/correlation/spreader_kernels.inc"
#endif
