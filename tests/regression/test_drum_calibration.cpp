// The rotating drum of an experiment (cases/drum_calibration): a drum of
// radius 69 mm and length 185 mm from an STL, 6,000 spheres of 5.95 mm, at
// 2.198 rad/s (Froude number 0.034, the rolling regime), with the contact
// parameters that reproduce the experiment's dynamic angle of repose in
// Lethe (e = 0.9, sliding friction 0.3, rolling friction 0.02, grains and
// drum alike). The angle, measured as `grains repose` does on the bed's
// surface next to the end walls (where the experiment films it), averaged
// over the frames of t = 2.5-5 s (the drum at full speed from 0.8 s: from
// 0.6 to 1.5 revolutions after it), must match the experiment's 26 degrees within the band of
// packing_references.yaml drum_calibration_angle.
#include <gtest/gtest.h>

#include "postprocess/surface_angle.hpp"
#include "tests/regression/packing_support.hpp"

namespace grains::test {
namespace {

using namespace packing;

TEST(DrumCalibration, DynamicAngleOfReposeMatchesTheExperiment) {
  const auto ref = reference("drum_calibration_angle");
  auto s = io::make_simulation(io::load_case(std::string(GRAINS_SOURCE_DIR) + "/cases/drum_calibration/case.yaml"));
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  const auto every = static_cast<std::int64_t>(std::llround(0.05 / sc.clock.dt));
  postprocess::SurfaceAngleOptions opt;
  opt.axis = 1;
  opt.radius = 0.069;
  opt.near_ends = 0.0225;  // the end bands of Lethe's measurement (|x| > 0.07 m of a half-length of 0.0925 m)
  std::vector<double> angle, residual;
  while (sc.clock.step < sc.clock.n_steps) {
    s.pipeline.step(sc);
    if (sc.clock.time < 2.5 || sc.clock.step % every != 0) continue;
    const postprocess::Frame f = sphere_frame(sc);
    const auto a = postprocess::surface_angle(f, opt);
    // Turning right-handed about +y, the drum's bottom moves towards -x and
    // carries the bed up on that side.
    EXPECT_LT(a.slope, 0) << "t = " << f.time << ": the surface must rise on the -x side";
    angle.push_back(a.angle_deg);
    residual.push_back(a.rms_residual);
  }
  std::cout << "drum_calibration: angle " << mean(angle) << " +- " << stddev(angle) << " deg over " << angle.size()
            << " frames, surface rms residual " << mean(residual) << " m\n";
  EXPECT_EQ(sc.particles.n_owned(), 6000u);
  ASSERT_GE(angle.size(), 45u);
  EXPECT_LT(mean(residual), 0.006);  // a grain diameter: a surface, not a heap
  expect_in_band(ref, mean(angle), "dynamic angle of repose, deg");
  record("drum_calibration", Record().num("angle", mean(angle)).num("std", stddev(angle)));
}

}  // namespace
}  // namespace grains::test
