// contact.model and a normal law's own keys (contact.<law>: {...}), read
// through the registry (sim/laws/normal_laws.hpp): accepted values reach the
// pair table, mistakes are reported with their location.
#include <gtest/gtest.h>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"
#include "tests/support/case_errors.hpp"
#include "sim/laws/normal_linear.hpp"

namespace grains::io {
namespace {

using test::errors_of;

const std::string kCase = R"(domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
materials:
  - {name: glass, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, friction: 0.5, restitution: 0.6}
  - {name: steel, density: 7800, youngs_modulus: 2.0e8, poisson_ratio: 0.3, friction: 0.2}
particles:
  - material: glass
    radius: 0.0005
    count: 10
    placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}
time: {dt: 1.0e-6, end: 1.0e-5}
)";

using L = sim::LinearNormal;

TEST(NormalLawKeys, LinearValuesAndDefaultsReachThePairTable) {
  auto c = parse_case(kCase + "contact:\n  model: linear\n  linear: {stiffness: 3.0e3}\n  pairs:\n"
                              "    - {materials: [glass, steel], linear: {stiffness: 5.0e3, damping: 0.1}}\n",
                      "case.yaml");
  EXPECT_EQ(c.scene.normal.name, "linear");
  auto s = make_simulation(std::move(c));
  const auto& glass = s.scene.pairs(0, 0);
  EXPECT_EQ(glass.normal[L::sMode], L::Stiffness);
  EXPECT_EQ(glass.normal[L::sK], 3e3);
  EXPECT_LT(glass.normal[L::sGamma], 0);  // from the restitution
  const double le = std::log(0.6);
  EXPECT_DOUBLE_EQ(glass.normal[L::sG1], -2 * le / std::sqrt(M_PI * M_PI + le * le));
  EXPECT_DOUBLE_EQ(glass.normal[L::sKappa], 2.0 / 7.0);  // the declared defaults
  EXPECT_DOUBLE_EQ(glass.normal[L::sX], 0.5);
  const auto& mixed = s.scene.pairs(0, 1);
  EXPECT_EQ(mixed.normal[L::sK], 5e3);
  EXPECT_EQ(mixed.normal[L::sGamma], 0.1);
  EXPECT_EQ(s.scene.pairs(1, 1).normal[L::sK], 3e3);
  // The default restitution of a material (steel gives none) is the declared 0.5.
  EXPECT_EQ(s.scene.materials[1].restitution, 0.5);
}

TEST(NormalLawKeys, HertzIsTheDefaultAndUnchanged) {
  auto s = make_simulation(parse_case(kCase, "case.yaml"));
  bool found = false;
  for (const auto& n : s.pipeline.stage_names())
    found = found || n == "force: force.pair_contacts<hertz+tangential:mindlin+rolling:none+cohesion:none>";
  EXPECT_TRUE(found);
}

TEST(NormalLawKeys, UnknownModelListsTheRegisteredOnes) {
  const auto m = errors_of(kCase + "contact: {model: hooke}\n");
  EXPECT_NE(m.find("case.yaml:11:18"), std::string::npos) << m;
  EXPECT_NE(m.find("hertz, linear"), std::string::npos) << m;
}

TEST(NormalLawKeys, LinearNeedsExactlyOneWayToGiveTheStiffness) {
  auto m = errors_of(kCase + "contact: {model: linear}\n");
  EXPECT_NE(m.find("give exactly one of stiffness, contact_time or characteristic_velocity (0 given)"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("case.yaml:11:"), std::string::npos) << m;
  m = errors_of(kCase + "contact: {model: linear, linear: {stiffness: 1.0e3, contact_time: 1.0e-4}}\n");
  EXPECT_NE(m.find("(2 given)"), std::string::npos) << m;
  m = errors_of(kCase + "contact: {model: linear, linear: {contact_time: 1.0e-4, damping: 1}}\n");
  EXPECT_NE(m.find("damping goes with stiffness"), std::string::npos) << m;
  m = errors_of(kCase + "contact: {model: linear, linear: {contact_time: 1.0e-4, damping_rate: 50}}\n");
  EXPECT_NE(m.find("damping_rate goes with stiffness"), std::string::npos) << m;
  m = errors_of(kCase + "contact: {model: linear, linear: {stiffness: 1.0e3, damping: 1, damping_rate: 50}}\n");
  EXPECT_NE(m.find("give damping or damping_rate, not both"), std::string::npos) << m;
  EXPECT_NE(m.find("case.yaml:11:"), std::string::npos) << m;
  m = errors_of(kCase + "contact: {model: linear, linear: {stiffness: 1.0e3, damping_rate: -1}}\n");
  EXPECT_NE(m.find("case.yaml:11:"), std::string::npos) << m;
  EXPECT_NE(m.find("damping_rate = -1 1/s is out of range; valid: >= 0"), std::string::npos) << m;
}

TEST(NormalLawKeys, LinearDampingRateReachesThePairTable) {
  auto s = make_simulation(parse_case(kCase + "contact: {model: linear, linear: {stiffness: 3.0e3, damping_rate: 50}}\n",
                                      "case.yaml"));
  const auto& glass = s.scene.pairs(0, 0);
  EXPECT_EQ(glass.normal[L::sRate], 50.0);
  EXPECT_LT(glass.normal[L::sGamma], 0);  // not an absolute damping
  double kn = 0, gn = 0;
  L::coefficients(0.001, 2e-4, glass, kn, gn);
  EXPECT_EQ(kn, 3e3);
  EXPECT_EQ(gn, 50.0 * 2e-4);  // gamma_n = rate x m*
}

TEST(NormalLawKeys, BadValuesAndUnknownKeysAreLocated) {
  auto m = errors_of(kCase + "contact: {model: linear, linear: {stiffness: -1}}\n");
  EXPECT_NE(m.find("case.yaml:11:46"), std::string::npos) << m;
  EXPECT_NE(m.find("valid: > 0"), std::string::npos) << m;
  m = errors_of(kCase + "contact: {model: linear, linear: {stifness: 1}}\n");
  EXPECT_NE(m.find("did you mean 'stiffness'?"), std::string::npos) << m;
}

TEST(NormalLawKeys, AnotherLawsKeysOrTangentialAreRefused) {
  auto m = errors_of(kCase + "contact: {linear: {stiffness: 1.0e3}}\n");
  EXPECT_NE(m.find("keys of the linear law given, but contact.model is hertz"), std::string::npos) << m;
  m = errors_of(kCase + "contact: {model: linear, tangential: mindlin, linear: {stiffness: 1.0e3}}\n");
  EXPECT_NE(m.find("tangential: mindlin does not pair with model: linear; use 'linear'"), std::string::npos) << m;
  m = errors_of(kCase + "contact: {tangential: linear}\n");
  EXPECT_NE(m.find("use 'mindlin'"), std::string::npos) << m;
}

TEST(NormalLawKeys, AdhesionNeedsAnAdhesiveLawAndIsLocated) {
  std::string sticky = kCase;
  sticky.replace(sticky.find("restitution: 0.6}"), 17, "restitution: 0.6, surface_energy: 0.05}");
  // Given to a law without adhesion: refused where it is given, naming the law that has it.
  auto m = errors_of(sticky);
  EXPECT_NE(m.find("case.yaml:3:126: adhesion (surface_energy or work_of_adhesion > 0) needs an adhesive normal "
                   "law, contact.model: dmt or jkr; model hertz has no adhesion and would ignore it"),
            std::string::npos)
      << m;
  m = errors_of(kCase + "contact:\n  model: linear\n  linear: {stiffness: 3.0e3}\n  pairs:\n"
                        "    - {materials: [glass, steel], work_of_adhesion: 0.1}\n");
  EXPECT_NE(m.find("case.yaml:15:53: adhesion"), std::string::npos) << m;
  EXPECT_NE(m.find("model linear has no adhesion"), std::string::npos) << m;
  // A negative surface energy or work of adhesion: out of range.
  std::string negative = kCase;
  negative.replace(negative.find("restitution: 0.6}"), 17, "restitution: 0.6, surface_energy: -0.05}");
  m = errors_of(negative + "contact: {model: dmt}\n");
  EXPECT_NE(m.find("materials[0]: surface_energy = -0.05 J/m^2 is out of range; valid: >= 0"), std::string::npos) << m;
  m = errors_of(kCase + "contact: {model: dmt, pairs: [{materials: [glass, steel], work_of_adhesion: -1}]}\n");
  EXPECT_NE(m.find("work_of_adhesion = -1 J/m^2 is out of range; valid: >= 0"), std::string::npos) << m;
  // Zero surface energy with any law is fine; with dmt the work of adhesion reaches the pair table.
  EXPECT_NO_THROW(make_simulation(parse_case(kCase + "contact: {model: dmt}\n", "case.yaml")));
  auto s = make_simulation(parse_case(sticky + "contact: {model: dmt}\n", "case.yaml"));
  EXPECT_DOUBLE_EQ(s.scene.pairs(0, 0).work_of_adhesion, 0.1);
  EXPECT_EQ(s.scene.pairs(0, 1).work_of_adhesion, 0.0);  // steel has none: 2 sqrt(0.05 * 0)
}

TEST(NormalLawKeys, TimeStepCheckedAgainstTheContactTime) {
  // dt = 1e-6 s: refused above t_c / pi, warned about above t_c / 20.
  auto m = errors_of(kCase + "contact: {model: linear, linear: {contact_time: 2.0e-6}}\n");
  EXPECT_NE(m.find("case.yaml:10:"), std::string::npos) << m;
  EXPECT_NE(m.find("is 0.5 contact times (t_c = 2e-06 s); above 0.3183"), std::string::npos) << m;
  EXPECT_EQ(m.find("dt_rayleigh"), std::string::npos) << m;  // a Rayleigh fraction says nothing of t_c
  std::string hertz = kCase;
  hertz.replace(hertz.find("dt: 1.0e-6"), 10, "dt: 1.0e-3");
  m = errors_of(hertz);
  EXPECT_NE(m.find("Rayleigh times (T_R = "), std::string::npos) << m;
  EXPECT_NE(m.find("or give time.dt_rayleigh instead"), std::string::npos) << m;
  auto s = make_simulation(parse_case(kCase + "contact: {model: linear, linear: {contact_time: 1.0e-5}}\n", "case.yaml"));
  ASSERT_EQ(s.c.scene.warnings.size(), 1u);
  EXPECT_NE(s.c.scene.warnings[0].find("0.1 contact times"), std::string::npos) << s.c.scene.warnings[0];
  auto quiet = make_simulation(parse_case(kCase + "contact: {model: linear, linear: {contact_time: 1.0e-4}}\n", "case.yaml"));
  EXPECT_TRUE(quiet.c.scene.warnings.empty());
}

TEST(NormalLawKeys, JkrRefusesWhatItHasNoPlaceForAtTheModel) {
  std::string sticky = kCase;
  sticky.replace(sticky.find("restitution: 0.6}"), 17, "restitution: 0.6, surface_energy: 0.05}");
  EXPECT_NO_THROW(make_simulation(parse_case(sticky + "contact: {model: jkr}\n", "case.yaml")));
  // Ellipsoids: JKR is a law of spheres; dmt is offered.
  std::string ell = sticky;
  ell.replace(ell.find("    count: 10\n"), 14, "    count: 10\n    shape: {type: ellipsoid, aspect_ratio: 2.0}\n");
  auto m = errors_of(ell + "contact: {model: jkr}\n");
  EXPECT_NE(m.find("case.yaml:12:18: "), std::string::npos) << m;
  EXPECT_NE(m.find("contact.model jkr is a law of spheres (and clumps of spheres); this scene has ellipsoids: use "
                   "model dmt"),
            std::string::npos)
      << m;
  // ARKODE: its state has no place for the contact state.
  std::string ark = sticky;
  ark.replace(ark.find("time: {dt: 1.0e-6, end: 1.0e-5}"), 31, "time: {dt: 1.0e-6, end: 1.0e-5, integrator: arkode}");
  m = errors_of(ark + "contact: {model: jkr}\n");
  EXPECT_NE(m.find("case.yaml:11:18: "), std::string::npos) << m;
  EXPECT_NE(m.find("use time.integrator: verlet (case.yaml:10:"), std::string::npos) << m;
  // SJKR cohesion on top of JKR adhesion.
  std::string coh = sticky;
  coh.replace(coh.find("surface_energy: 0.05}"), 21, "surface_energy: 0.05, cohesion_energy_density: 1.0e4}");
  m = errors_of(coh + "contact: {model: jkr}\n");
  EXPECT_NE(m.find("contact.model jkr is itself the adhesion; cohesion (sjkr"), std::string::npos) << m;
}

TEST(NormalLawKeys, JkrTimeStepCheckedAgainstTheAdhesiveNeck) {
  // Very sticky soft grains (w = 6 J/m^2, E = 1e7 Pa, R = 0.5 mm): the
  // period of the adhesive neck, sqrt(m*/k0) = 3.17e-5 s, is shorter than the
  // Rayleigh time 4.33e-5 s, so it is what the time step is checked against.
  std::string sticky = kCase;
  sticky.replace(sticky.find("restitution: 0.6}"), 17, "restitution: 0.6, surface_energy: 3.0}");
  auto with_dt = [&](const std::string& dt) {
    std::string c = sticky;
    c.replace(c.find("dt: 1.0e-6"), 10, "dt: " + dt);
    return c + "contact: {model: jkr}\n";
  };
  // 1.15e-5 s: 0.27 Rayleigh times (no warning from them), 0.36 neck times (a warning).
  auto s = make_simulation(parse_case(with_dt("1.15e-5"), "case.yaml"));
  ASSERT_EQ(s.c.scene.warnings.size(), 1u);
  EXPECT_NE(s.c.scene.warnings[0].find("case.yaml:10:"), std::string::npos) << s.c.scene.warnings[0];
  EXPECT_NE(s.c.scene.warnings[0].find("0.3628 neck times (t_neck"), std::string::npos) << s.c.scene.warnings[0];
  // 3.5e-5 s: 0.81 Rayleigh times, 1.1 neck times: refused.
  auto m = errors_of(with_dt("3.5e-5"));
  EXPECT_NE(m.find("case.yaml:10:"), std::string::npos) << m;
  EXPECT_NE(m.find("1.104 neck times"), std::string::npos) << m;
  // The same step with Hertz: under the Rayleigh limits, no word.
  std::string hertz = with_dt("1.15e-5");
  hertz.replace(hertz.find("surface_energy: 3.0"), 19, "surface_energy: 0.0");
  EXPECT_TRUE(make_simulation(parse_case(hertz, "case.yaml")).c.scene.warnings.empty());
}

}  // namespace
}  // namespace grains::io
