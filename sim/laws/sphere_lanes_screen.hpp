#pragma once
// The two list passes of the sphere lanes (sphere_lanes_stage.cpp) eight
// entries per instruction, the second fused into the kernel, for processors
// with AVX-512F, and four per instruction with AVX2 (issue 26: the pair
// kernel near its limit). Chosen at run time beside the kernel's copy of the
// same instruction set; GRAINS_SIMD=baseline or =scalar keeps the scalar
// passes.
//
// The scalar passes store, for every list entry, nine values into the batch
// and, for every touching one, fourteen more, one at a time: on the 10^4 bed
// they were about half of the pair stage's time (perf, 2026-12-02). Here an
// entry's partner fields come in by gathers (AVX2: loads of three doubles and a
// transpose, faster there than its gathers), the touching entries are
// packed into the next free lanes by a compress (AVX2: a permutation from a
// table), and eight (four) lanes are stored by one instruction. The arithmetic is the scalar passes', operation by
// operation in their order (d = x_i - x_j, |d|^2 = (dx dx + dy dy) + dz dz,
// r_c = (r_i + r_j) + reach, touching when !(|d|^2 >= r_c^2); v_i - v_j;
// R* and m* as the list computes them), so the bits are the same
// (tests/unit/laws/test_sphere_lanes.cpp runs both and compares).
//
// The first pass is written once, in sphere_lanes_screen.inc, which each
// instruction set's unit includes with its own few operations (the lane
// count, gathers, masks, the packing).
//
// Plain pointers only: this header and its AVX-512 and AVX2 units see no
// Eigen and no inline function of the project that another unit compiles
// for the baseline (the linker keeps one copy of an inline function).
#include <cstddef>
#include <cstdint>

#include "sim/laws/sphere_lanes.hpp"

namespace grains::sim {

/// What the passes read and write besides the batch. x, v, omega: three
/// doubles per particle (Eigen::Vector3d arrays).
struct SphereScreenFields {
  const std::uint32_t* row_start = nullptr;
  std::size_t rows = 0;  // the list's rows (row_start's length - 1; the fields hold at least as many)
  const std::uint32_t* partner = nullptr;
  std::size_t entries = 0;  // partner's length (may_touch's, history's / 3)
  std::uint8_t* may_touch = nullptr;
  double* history = nullptr;  // three per entry
  const double* x = nullptr;
  const double* radius = nullptr;
  const double* v = nullptr;
  const double* omega = nullptr;
  const double* mass = nullptr;
  const double* f = nullptr;       // prefetched only
  const double* torque = nullptr;  // prefetched only
  double reach = 0;
  bool prefetch = false;  // a scene larger than the cache (the stage prefetches: the kernel gathers its partners)
  // Per lane of the batch: the entry's row, entry and partner.
  std::uint32_t* row_of = nullptr;
  std::uint32_t* entry_of = nullptr;
  std::uint32_t* partner_of = nullptr;
};

/// The first pass from entry k of row i on: each entry's may_touch set (and
/// the spring of a pair that came apart cleared), the touching entries'
/// geometry into lanes n, n+1, ... of b. Stops at the end of row row_end - 1
/// or as soon as b holds SphereContactBatch::kSize lanes or more (at most
/// kSize + kPad - 1); returns the lane count, with i and k where to go on.
/// Prefetch: also asks for the fields the second pass and the force sums
/// will read (scenes larger than the cache).
using SphereScreenFn = int (*)(const SphereScreenFields& in, SphereContactBatch& b, int n, std::size_t& i,
                               std::uint32_t& k, std::size_t row_end, bool prefetch);
/// The kernel (sphere_lanes.hpp) for lanes [0, b.count rounded up to eight)
/// with the second pass fused in: one material, no frozen grains; it gathers
/// the relative velocity, both spins, the spring, R* and m* itself, so every
/// lane up to the rounded count must hold a valid row, entry and partner in
/// in.row_of, in.entry_of, in.partner_of.
using SphereGatheredKernelFn = void (*)(const SphereScreenFields& in, SphereContactBatch& b);

/// The pass and kernel of the kernel's copy (AVX-512, or AVX2 with four
/// entries per instruction: sphere_lanes_screen_avx2.cpp), or null where the
/// processor has neither, the build has no copy of them, or GRAINS_SIMD caps
/// the instruction set below AVX2.
SphereScreenFn sphere_screen();
SphereGatheredKernelFn sphere_kernel_gathered();

}  // namespace grains::sim
