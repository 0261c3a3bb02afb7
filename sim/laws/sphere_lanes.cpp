// Hertz–Mindlin sphere contacts in lanes: see sphere_lanes.hpp. The
// arithmetic (sphere_lanes.inc) is compiled for the baseline instruction set
// here and with AVX2 in sphere_lanes_avx2.cpp; the copy is chosen once, at
// run time, by the CPU (GRAINS_SIMD=baseline forces the baseline copy).
#include "sim/laws/sphere_lanes.inc"

#include <cstdlib>

namespace grains::sim {

#if GRAINS_LANES_AVX2
namespace isa_avx {
void hertz_mindlin_lanes_isa(SphereContactBatch&);
}  // namespace isa_avx
#endif

namespace {

struct LaneCopy {
  const char* name;
  void (*kernel)(SphereContactBatch&);
};

const LaneCopy& lane_copy() {
  static const LaneCopy copy = []() -> LaneCopy {
    const LaneCopy baseline{contact::kPack == 4 ? "avx (native build)" : "baseline", hertz_mindlin_lanes_isa};
#if GRAINS_LANES_AVX2
    const char* env = std::getenv("GRAINS_SIMD");
    if (env && std::strcmp(env, "baseline") == 0) return baseline;
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2")) return {"avx2", isa_avx::hertz_mindlin_lanes_isa};
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

}  // namespace grains::sim
