// PW85 and contact geometry of many pairs in lockstep: see pw85_lanes.hpp.
// The arithmetic (pw85_lanes.inc) is compiled for the baseline instruction
// set here and with AVX2 in pw85_lanes_avx2.cpp; the copy is chosen once, at
// run time, by the CPU (GRAINS_SIMD=baseline forces the baseline copy).
#include "contact/ellipsoid/pw85_lanes.inc"

#include <cstdlib>
#include <cstring>

namespace grains::contact {

#if GRAINS_LANES_AVX2
namespace isa_avx {
void pw85_contact_lanes_isa(const Pw85LaneJob*, std::size_t, Pw85LaneResult*, double, bool, int);
void contact_geometry_lanes_isa(const PairGeometryJob*, std::size_t, ContactGeometry*);
}  // namespace isa_avx
#endif

namespace {

struct LaneCopy {
  const char* name;
  void (*pw85)(const Pw85LaneJob*, std::size_t, Pw85LaneResult*, double, bool, int);
  void (*geometry)(const PairGeometryJob*, std::size_t, ContactGeometry*);
};

const LaneCopy& lane_copy() {
  static const LaneCopy copy = []() -> LaneCopy {
    // This file's own copy: the baseline instruction set (AVX in a
    // -march=native build on such a CPU, and then there is no second copy).
    const LaneCopy baseline{kPack == 4 ? "avx (native build)" : "baseline", pw85_contact_lanes_isa,
                            contact_geometry_lanes_isa};
#if GRAINS_LANES_AVX2
    const char* env = std::getenv("GRAINS_SIMD");
    if (env && std::strcmp(env, "baseline") == 0) return baseline;
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2"))
      return {"avx2", isa_avx::pw85_contact_lanes_isa, isa_avx::contact_geometry_lanes_isa};
#endif
    return baseline;
  }();
  return copy;
}

}  // namespace

void pw85_contact_lanes(const Pw85LaneJob* jobs, std::size_t count, Pw85LaneResult* out, double tolerance,
                        bool stop_if_separated, int max_iterations) {
  lane_copy().pw85(jobs, count, out, tolerance, stop_if_separated, max_iterations);
}

void contact_geometry_lanes(const PairGeometryJob* jobs, std::size_t count, ContactGeometry* out) {
  lane_copy().geometry(jobs, count, out);
}

const char* lanes_instruction_set() { return lane_copy().name; }

}  // namespace grains::contact
