#pragma once
// Hertz–Mindlin contacts of sphere pairs, kLanes at a time (issue 26: the
// pair kernel near its limit).
//
// One sphere contact is a chain of dependent square roots and divisions
// (|d|, 1/|d|, sqrt R*, sqrt d, the damping's sqrt, the Coulomb limit's):
// evaluated one after the other the processor mostly waits on them. The
// force stage (pair_contact_stage.hpp) therefore collects the touching
// pairs of the list into a batch, structure of arrays, and this kernel
// computes the batch in lockstep lanes (contact/ellipsoid/lanes.hpp: two
// doubles per SSE2 instruction in the baseline copy, four per AVX instruction
// in the AVX2 copy, eight per instruction in the AVX-512 copy, chosen at run
// time). The stage then adds the forces to the
// particles in list order, as the scalar loop does.
//
// Every lane does the IEEE operations of the scalar law (normal_hertz.hpp,
// tangential.hpp, contact_law.hpp, the geometry of pair_contact_stage.hpp) in
// the same order, and no copy contracts them into FMAs, so results are
// bitwise those of the scalar code (tests/unit/laws/test_sphere_lanes.cpp
// compares them pair by pair; same_results.sh run by run).
#include <cstddef>

namespace grains::sim {

/// A batch of touching sphere pairs: inputs, and the outputs the kernel
/// writes. Lanes past `count` up to a multiple of kPad must hold a finite
/// contact (the stage repeats the last one there); their outputs are unused.
struct SphereContactBatch {
  static constexpr int kSize = 32;  // lanes at which a batch is computed; a multiple of kPad
  static constexpr int kPad = 8;    // a multiple of every copy's lane count (AVX-512: 8)
  // Room: the AVX-512 list passes (sphere_lanes_screen.hpp) store eight
  // lanes at a time, so a batch may reach kSize + kPad - 1 lanes.
  static constexpr int kRoom = kSize + kPad;
  int count = 0;
  double dt = 0;
  // Geometry: d = x_i - x_j, |d|^2; the radii.
  alignas(64) double dx[kRoom], dy[kRoom], dz[kRoom], d2[kRoom], ri[kRoom], rj[kRoom];
  // Motion: v_i - v_j, omega_i, omega_j.
  alignas(64) double vx[kRoom], vy[kRoom], vz[kRoom];
  alignas(64) double wix[kRoom], wiy[kRoom], wiz[kRoom], wjx[kRoom], wjy[kRoom], wjz[kRoom];
  // The pair's R* and m* (NeighborList::PairConstants) and its material pair's
  // E*, G*, damping a, tangential damping ratio, friction (PairParams).
  alignas(64) double R[kRoom], m[kRoom], E[kRoom], G[kRoom], a[kRoom], tdr[kRoom], mu[kRoom];
  // The tangential spring: read, and written back updated.
  alignas(64) double hx[kRoom], hy[kRoom], hz[kRoom];
  // Outputs: the force on i (j gets minus it) and the torques on i and j.
  alignas(64) double fx[kRoom], fy[kRoom], fz[kRoom];
  alignas(64) double tix[kRoom], tiy[kRoom], tiz[kRoom], tjx[kRoom], tjy[kRoom], tjz[kRoom];
};

/// Computes lanes [0, count rounded up to the lane count) of the batch.
void hertz_mindlin_lanes(SphereContactBatch& b);
/// False when GRAINS_SIMD=scalar asks the force stages for the scalar loop
/// (read when a stage is made: for comparisons of the two).
bool sphere_lanes_enabled();
/// The instruction set of the copy in use ("baseline", "avx2", "avx512"; GRAINS_SIMD=baseline or =avx2 caps it).
const char* sphere_lanes_instruction_set();

}  // namespace grains::sim
