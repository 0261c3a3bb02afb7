// Hertz–Mindlin sphere contacts in lanes: see sphere_lanes.hpp. The
// arithmetic (sphere_lanes.inc) is compiled for the baseline instruction set
// here, with AVX2 in sphere_lanes_avx2.cpp and with AVX-512 in
// sphere_lanes_avx512.cpp; the copy is chosen once, at run time, by the CPU
// (GRAINS_SIMD=baseline or =avx2 caps it).
#include "sim/laws/sphere_lanes.inc"

#include <cstdlib>

#include "sim/laws/sphere_lanes_screen.hpp"

namespace grains::sim {

#if GRAINS_LANES_AVX2
namespace isa_avx {
void hertz_mindlin_lanes_isa(SphereContactBatch&);
int screen_rows(const SphereScreenFields&, SphereContactBatch&, int, std::size_t&, std::uint32_t&, std::size_t, bool);
void hertz_mindlin_lanes_gathered(const SphereScreenFields&, SphereContactBatch&);
}  // namespace isa_avx
namespace isa_avx512 {
void hertz_mindlin_lanes_isa(SphereContactBatch&);
int screen_rows(const SphereScreenFields&, SphereContactBatch&, int, std::size_t&, std::uint32_t&, std::size_t, bool);
void hertz_mindlin_lanes_gathered(const SphereScreenFields&, SphereContactBatch&);
}  // namespace isa_avx512
#endif

namespace {

struct LaneCopy {
  const char* name;
  void (*kernel)(SphereContactBatch&);
  // The list pass and gathered kernel of the same instruction set (AVX-512 or AVX2).
  SphereScreenFn screen = nullptr;
  SphereGatheredKernelFn gathered = nullptr;
};

const LaneCopy& lane_copy() {
  static const LaneCopy copy = []() -> LaneCopy {
    const LaneCopy baseline{contact::kPack == 4 ? "avx (native build)" : "baseline", hertz_mindlin_lanes_isa};
#if GRAINS_LANES_AVX2
    const char* env = std::getenv("GRAINS_SIMD");
    if (env && std::strcmp(env, "baseline") == 0) return baseline;
    __builtin_cpu_init();
    const bool cap_avx2 = env && std::strcmp(env, "avx2") == 0;
    if (!cap_avx2 && __builtin_cpu_supports("avx512f"))
      return {"avx512", isa_avx512::hertz_mindlin_lanes_isa, isa_avx512::screen_rows,
              isa_avx512::hertz_mindlin_lanes_gathered};
    if (__builtin_cpu_supports("avx2"))
      return {"avx2", isa_avx::hertz_mindlin_lanes_isa, isa_avx::screen_rows, isa_avx::hertz_mindlin_lanes_gathered};
#endif
    return baseline;
  }();
  return copy;
}

}  // namespace

void hertz_mindlin_lanes(SphereContactBatch& b) { lane_copy().kernel(b); }

bool sphere_lanes_enabled() {
  const char* env = std::getenv("GRAINS_SIMD");
  return !(env && std::strcmp(env, "scalar") == 0);
}

const char* sphere_lanes_instruction_set() { return lane_copy().name; }

SphereScreenFn sphere_screen() { return lane_copy().screen; }
SphereGatheredKernelFn sphere_kernel_gathered() { return lane_copy().gathered; }

}  // namespace grains::sim
