// Regression: packing of poured clumps.
//
// * Dimers of bond aspect ratio 1.5 (two balls of radius a, centres a apart)
//   pack denser than spheres of the same volume under the same frictionless
//   pour (reference, ../shared/REFERENCES.md: frictionless jammed dimers
//   reach a maximum of about 0.70 near aspect ratio 1.4-1.5, spheres 0.64;
//   Baule et al., Nat. Commun. 4 (2013)).
// * The first resolution step of the cube: at grid 4 (8 balls) the
//   decomposition is nearly a sphere, at grid 6 (40 balls) it has faces and
//   edges, and the poured bed is looser by far more than the seed noise
//   (seed 1 of the long sweep ClumpRegressionLong.CubeResolutionSweep, which
//   records phi against n3 in docs/decomposition.md).
//
// The solid fraction of a bulk box is measured on a grid of sample points
// (a point counts once however many balls cover it, so the overlapping balls
// of a clump are not counted twice); for spheres it agrees with the exact
// sphere-box volumes of postprocess/packing_fraction.
#include <gtest/gtest.h>

#include "tests/regression/clump/clump_pour.hpp"

namespace grains::test {
namespace {

TEST(ClumpRegression, DimersOfAspectRatio1p5PackDenserThanSpheres) {
  const packing::Reference rise = packing::reference("dimer_rise");
  const double d = 0.001, w = 10 * d;
  const int n = 1200;
  const auto spheres = pour("{type: sphere}", d / 2, d, n, w, 0.45);
  // Dimer of the sphere's volume: V = 2.25 pi a^3 = pi d^3 / 6.
  const double a = std::cbrt(1.0 / 13.5) * d;
  const auto dimers = pour("{type: clump, file: " + dimer_file(1.0, 1.0) + "}", 1.5 * a, d, n, w, 0.45);
  std::cout << "frictionless pour, " << n << " grains: spheres phi = " << spheres.phi << " (exact "
            << spheres.phi_exact_spheres << "), dimers (aspect 1.5) phi = " << dimers.phi << "\n";
  RecordProperty("phi_spheres", std::to_string(spheres.phi));
  RecordProperty("phi_dimers", std::to_string(dimers.phi));
  EXPECT_EQ(dimers.bodies, static_cast<std::size_t>(n));
  EXPECT_NEAR(spheres.phi, spheres.phi_exact_spheres, 0.003);  // the sampler against exact volumes
  EXPECT_LT(spheres.speed, 0.02);
  EXPECT_LT(dimers.speed, 0.02);
  EXPECT_GT(spheres.phi, 0.60);
  EXPECT_LT(spheres.phi, 0.66);
  packing::record("dimer_ci", packing::Record()
                                 .str("case", "1,200 frictionless spheres or dimers (aspect 1.5), e = 0.1")
                                 .num("phi_spheres", spheres.phi)
                                 .num("phi_dimers", dimers.phi)
                                 .num("rise", dimers.phi - spheres.phi));
  packing::expect_in_band(rise, dimers.phi - spheres.phi, "dimers - spheres");
}

TEST(ClumpRegression, CubeFirstResolutionStepLoosensThePour) {
  const packing::Reference step = packing::reference("clump_resolution_first_step");
  PeriodicPourConfig c;  // seed 1 of the long sweep
  c.grid = 4;
  const auto coarse = pour_periodic(c);
  c.grid = 6;
  const auto fine = pour_periodic(c);
  for (const auto* r : {&coarse, &fine}) {
    EXPECT_EQ(r->bodies, static_cast<std::size_t>(c.count));
    EXPECT_LT(r->rms_speed, packing::settled_speed());
  }
  packing::record("clump_resolution_ci", packing::Record()
                                             .str("case", "250 frictional cubes, 6 mm periodic box, seed 1, grid 4 and 6")
                                             .num("phi_grid4", coarse.phi)
                                             .num("phi_grid6", fine.phi)
                                             .num("step", fine.phi - coarse.phi));
  packing::expect_in_band(step, fine.phi - coarse.phi, "phi(grid 6) - phi(grid 4), seed 1");
}

}  // namespace
}  // namespace grains::test
