// The DMT adhesive normal law (sim/laws/normal_dmt.hpp), run as cases
// through the real stages and the Verlet integrator:
//  - without adhesion it is the Hertz law, bit for bit (impacts on a wall
//    and of two spheres);
//  - the pull-off force is 2 pi w R*: a sphere held to a plane wall by
//    adhesion, pulled away by a body force of 99.5 % of 2 pi w R, stays;
//    at 100.5 % it leaves (the 0.5 %);
//  - the work of adhesion of a pair is 2 sqrt(g_a g_b) of the materials'
//    surface energies, and contact.pairs[].work_of_adhesion overrides it;
//  - a slow pair of adhesive spheres sticks where Hertz grains bounce.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "tests/physics/contact/impact.hpp"

namespace grains::test {
namespace {

constexpr double E = 1e7, nu = 0.3, rho = 2500, R = 0.001;
const double mass = rho * 4.0 / 3.0 * M_PI * R * R * R;

TEST(DmtLaw, WithoutAdhesionIsHertzExactly) {
  expect_hertz_impacts("{model: dmt, tangential: none}", E, nu, rho, R);
}

// A sphere (R, g surface energy, both bodies one material: w = 2 g) resting on
// the plane x = 0 at the overlap where the Hertz force balances F_c - T, T =
// f F_c the body force pulling it off along +x; returns its overlap after
// `end` seconds (< 0: it left; pulled off, it flies about 0.6 R in 5 ms).
// `contact` is the case's contact section (the law, a pair override).
double pulled(double f, double g, const std::string& contact, double end = 0.005) {
  const double w = 2 * g, Fc = 2 * M_PI * w * R;
  const double Estar = 1.0 / (2 * (1 - nu * nu) / E);
  const double K = 4.0 / 3.0 * Estar * std::sqrt(R);
  const double d0 = std::pow(0.005 * Fc / K, 2.0 / 3.0);  // the balance at f = 0.995
  const std::string y = pulled_case(E, nu, rho, R, g, f * Fc / mass, contact,
                                    "{type: plane, point: [0, 0, 0], normal: [1, 0, 0], material: m}", R - d0, 0, "", end);
  auto s = from_yaml(y);
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  EXPECT_NEAR(R - sc.particles.x[0][0], d0, 1e-3 * d0) << "placed at the balance";
  while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
  return R - sc.particles.x[0][0];
}

TEST(DmtLaw, PullOffForceIsTwoPiWR) {
  const std::string dmt = "{model: dmt, tangential: none}";
  EXPECT_GT(pulled(0.995, 0.05, dmt), 0) << "held below the pull-off force";
  EXPECT_LT(pulled(1.005, 0.05, dmt), -0.1 * R) << "pulled off above it";
  // Another strength, the same rule.
  EXPECT_GT(pulled(0.995, 0.4, dmt), 0);
  EXPECT_LT(pulled(1.005, 0.4, dmt), -0.1 * R);
}

TEST(DmtLaw, PairOverrideGivesTheWorkOfAdhesion) {
  // The materials say w = 2 * 0.05 = 0.1; the pair override 0.2 doubles F_c,
  // so a pull of 0.995 F_c(0.1) * 1.5 that would tear the first off holds.
  const std::string over = "{model: dmt, tangential: none, pairs: [{materials: [m, m], work_of_adhesion: 0.2}]}";
  EXPECT_GT(pulled(1.5 * 0.995, 0.05, over), 0);
  EXPECT_LT(pulled(1.5 * 0.995, 0.05, "{model: dmt, tangential: none}"), -0.1 * R);
}

TEST(DmtLaw, MixedSurfaceEnergiesGiveTheGeometricMean) {
  std::ostringstream y;
  y << "domain: {min: [-1, -1, -1], max: [1, 1, 1]}\nmaterials:\n"
    << "  - {name: a, density: 1000, youngs_modulus: 1e7, poisson_ratio: 0.3, surface_energy: 0.02}\n"
    << "  - {name: b, density: 1000, youngs_modulus: 1e7, poisson_ratio: 0.3, surface_energy: 0.08}\n"
    << "contact: {model: dmt}\nparticles:\n" << single("p", "a", sim::Vec3::Zero(), 0.01, sim::Vec3::Zero())
    << "time: {dt: 1e-5, end: 1e-5}\n";
  auto s = from_yaml(y.str());
  EXPECT_DOUBLE_EQ(s.scene.pairs(0, 1).work_of_adhesion, 2 * std::sqrt(0.02 * 0.08));
  EXPECT_DOUBLE_EQ(s.scene.pairs(0, 0).work_of_adhesion, 0.04);
  EXPECT_DOUBLE_EQ(s.scene.pairs(1, 1).work_of_adhesion, 0.16);
}

TEST(DmtLaw, SlowAdhesiveSpheresStickWhereHertzGrainsBounce) {
  // Two spheres approaching at +-1 mm/s: the DMT pair (w = 0.1 J/m^2) ends
  // in contact at rest relative to each other; the Hertz pair separates.
  auto run = [](const std::string& model, double g) {
    std::ostringstream y;
    y.precision(17);
    const double gap = 0.001 * R, v = 0.001;
    y << "domain: {min: [" << -10 * R << ", " << -2 * R << ", " << -2 * R << "], max: [" << 10 * R << ", " << 2 * R
      << ", " << 2 * R << "]}\n";
    y << "materials:\n  - {name: m, density: " << rho << ", youngs_modulus: " << E << ", poisson_ratio: " << nu
      << ", restitution: 0.5, surface_energy: " << g << "}\n";
    y << "contact: {model: " << model << ", tangential: none}\n";
    y << "particles:\n" << single("a", "m", sim::Vec3(-R - gap, 0, 0), R, sim::Vec3(v, 0, 0))
      << single("b", "m", sim::Vec3(R + gap, 0, 0), R, sim::Vec3(-v, 0, 0));
    y << "time: {dt_rayleigh: 0.1, end: 0.01}\n";
    auto s = from_yaml(y.str());
    auto& sc = s.scene;
    s.pipeline.initialize(sc);
    while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
    const auto& p = sc.particles;
    const std::size_t a = index_of(p, 0), b = index_of(p, 1);
    return std::pair{2 * R - (p.x[b] - p.x[a]).norm(), (p.v[b] - p.v[a]).norm()};
  };
  const auto [d_dmt, v_dmt] = run("dmt", 0.05);
  const auto [d_hertz, v_hertz] = run("hertz", 0.0);
  EXPECT_GT(d_dmt, 0) << "the adhesive pair stays in contact";
  EXPECT_LT(v_dmt, 1e-5) << "at rest relative to each other";
  EXPECT_LT(d_hertz, 0) << "the Hertz pair bounced apart";
  EXPECT_NEAR(v_hertz, 0.002 * 0.5, 0.0002) << "with its restitution";
}

}  // namespace
}  // namespace grains::test
