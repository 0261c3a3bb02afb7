// The rotating drum of cases/rotating_drum (a closed STL drum, 1,800 spheres,
// 10 rpm: the rolling regime) at CI length: the bed's free surface is flat
// (rolling, not cascading: small residual about the fitted line), no grain
// leaves the drum, and the dynamic angle of repose rises with the grains'
// friction (0.2 against 0.5) by more than the frame-to-frame scatter
// (packing_references.yaml: drum_angle_friction). Measured with the method of
// `grains repose` (postprocess/surface_angle.hpp) every 0.05 s from 1.5 s, a
// third of a revolution after the drum reached full speed.
#include <gtest/gtest.h>

#include "postprocess/surface_angle.hpp"
#include "tests/regression/packing_support.hpp"

namespace grains::test {
namespace {

using namespace packing;

struct Drum {
  std::vector<double> angle, residual;
  std::size_t n = 0;
  double mean() const { return packing::mean(angle); }
};

Drum spin(double mu) {
  const std::string path = std::string(GRAINS_SOURCE_DIR) + "/cases/rotating_drum/case.yaml";
  auto s = io::make_simulation(io::load_case(
      path, {"materials.0.friction=" + std::to_string(mu), "walls.0.start=0.3", "walls.0.ramp=0.3", "time.end=3.3"}));
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  Drum d;
  const auto every = static_cast<std::int64_t>(std::llround(0.05 / sc.clock.dt));
  postprocess::SurfaceAngleOptions opt;
  opt.axis = 1;
  opt.radius = 0.05;
  while (sc.clock.step < sc.clock.n_steps) {
    s.pipeline.step(sc);
    if (sc.clock.time < 1.5 || sc.clock.step % every != 0) continue;
    const postprocess::Frame f = sphere_frame(sc);
    const auto a = postprocess::surface_angle(f, opt);
    d.angle.push_back(a.angle_deg);
    d.residual.push_back(a.rms_residual);
  }
  d.n = sc.particles.n_owned();
  std::cout << "drum mu = " << mu << ": angle " << d.mean() << " +- " << stddev(d.angle) << " deg over "
            << d.angle.size() << " frames, surface rms residual " << packing::mean(d.residual) << " m\n";
  return d;
}

TEST(MeshDrum, DynamicAngleOfReposeRisesWithFrictionOnAFlatRollingSurface) {
  const auto ref = reference("drum_angle_friction");
  const Drum smooth = spin(0.2), rough = spin(0.5);
  for (const auto* d : {&smooth, &rough}) {
    EXPECT_EQ(d->n, 1800u);
    ASSERT_GE(d->angle.size(), 30u);
    EXPECT_LT(packing::mean(d->residual), 0.0015);  // half a grain diameter: a flat surface
  }
  expect_in_band(ref, rough.mean() - smooth.mean(), "angle(mu 0.5) - angle(mu 0.2), deg");
  record("mesh_drum", Record().num("angle_mu02", smooth.mean()).num("angle_mu05", rough.mean())
                          .num("std_mu02", stddev(smooth.angle)).num("std_mu05", stddev(rough.angle)));
}

}  // namespace
}  // namespace grains::test
