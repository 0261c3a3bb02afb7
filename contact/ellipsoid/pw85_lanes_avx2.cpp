// The lockstep PW85 and geometry arithmetic (pw85_lanes.inc) compiled with
// AVX2 (four lanes per instruction), without FMA contraction so that it gives
// the baseline copy's bits; chosen at run time by pw85_lanes.cpp.
#if !defined(__AVX2__)
#error "pw85_lanes_avx2.cpp must be compiled with -mavx2"
#endif
#include "contact/ellipsoid/pw85_lanes.inc"
