// time.integrator and the ARKODE keys: parsed, validated with locations,
// and the pipeline they assemble.
#include <gtest/gtest.h>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"
#include "tests/support/case_errors.hpp"
#include "sim/integrate/arkode.hpp"

namespace grains::io {
namespace {

using test::errors_of;

std::string with_time(const std::string& time_block, const std::string& extra = "") {
  return R"(domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
gravity: [0, 0, -9.81]
materials:
  - {name: glass, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, friction: 0.5}
particles:
  - {material: glass, radius: 0.0005, count: 10, placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}}
time:
)" + time_block + extra;
}

TEST(IntegratorKeys, VerletIsTheDefault) {
  auto s = make_simulation(parse_case(with_time("  dt: 1.0e-6\n  end: 1.0e-5\n"), "case.yaml"));
  EXPECT_EQ(s.c.scene.integrator, sim::Integrator::Verlet);
  EXPECT_EQ(s.pipeline.stage_names().front(), "drift: verlet.kick_drift+rotation+force_start");
  EXPECT_EQ(s.scene.neighbors.history_size(), 3);
}

TEST(IntegratorKeys, ArkodeWithTolerancesAndOrder) {
  auto s = make_simulation(parse_case(
      with_time("  dt: 1.0e-6\n  end: 1.0e-5\n  integrator: arkode\n  rtol: 1.0e-5\n  atol: 1.0e-7\n  order: 3\n",
                "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass, velocity: [0.1, 0, 0]}\n"),
      "case.yaml"));
  const auto& sc = s.c.scene;
  EXPECT_EQ(sc.integrator, sim::Integrator::Arkode);
  EXPECT_DOUBLE_EQ(sc.arkode.rtol, 1e-5);
  EXPECT_DOUBLE_EQ(sc.arkode.atol, 1e-7);
  EXPECT_EQ(sc.arkode.order, 3);
  // One driver in the drift phase; no Verlet stages, no wall mover (the
  // driver moves the walls to each trial time); the laws carry their
  // history in the ODE state: [spring | rate] per contact.
  const std::vector<std::string> stages{
      "drift: arkode.erk(order 3, rtol 1e-05, atol 1e-07; steps <= dt, contact history in the ODE state)",
      "neighbor: neighbor.verlet_list(skin trigger)",
      "force: force.clear+torque+gravity",
      "force: force.pair_contacts<hertz+tangential:mindlin+rolling:none+cohesion:none+history:ode_state>",
      "force: force.walls<hertz+tangential:mindlin+rolling:none+cohesion:none+history:ode_state>"};
  EXPECT_EQ(s.pipeline.stage_names(), stages);
  EXPECT_EQ(s.scene.neighbors.history_size(), 6);
  EXPECT_EQ(s.scene.particles.wall_history_size(), 6);
  EXPECT_TRUE(s.pipeline.stages().front()->is_driver());
  EXPECT_NE(dynamic_cast<const sim::ArkodeIntegrator*>(s.pipeline.stages().front().get()), nullptr);
}

TEST(IntegratorKeys, ArkodeMayStepBeyondTheRayleighTime) {
  // Verlet refuses dt above the Rayleigh time and warns above 0.3 of it;
  // for ARKODE dt only bounds the adaptive steps.
  EXPECT_NE(errors_of(with_time("  dt: 1.0e-3\n  end: 1.0e-2\n")).find("Rayleigh times"), std::string::npos);
  auto s = make_simulation(parse_case(with_time("  dt: 1.0e-3\n  end: 1.0e-2\n  integrator: arkode\n"), "case.yaml"));
  EXPECT_TRUE(s.c.scene.warnings.empty());
  EXPECT_EQ(s.scene.clock.n_steps, 10);
}

TEST(IntegratorKeys, BadValuesSayWhereAndWhatIsValid) {
  const auto unknown = errors_of(with_time("  dt: 1.0e-6\n  end: 1.0e-5\n  integrator: rk4\n"));
  EXPECT_NE(unknown.find("case.yaml:10:15: time: integrator = 'rk4' is not valid"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("valid: verlet, arkode"), std::string::npos) << unknown;
  const auto typo = errors_of(with_time("  dt: 1.0e-6\n  end: 1.0e-5\n  integrator: arkod\n  rtol: 1.0e-6\n"));
  EXPECT_NE(typo.find("did you mean 'arkode'?"), std::string::npos) << typo;
  EXPECT_EQ(typo.find("applies to integrator: arkode"), std::string::npos) << "one error for one mistake: " << typo;

  const auto range = errors_of(
      with_time("  dt: 1.0e-6\n  end: 1.0e-5\n  integrator: arkode\n  rtol: 0\n  atol: -1.0e-9\n  order: 9\n"));
  EXPECT_NE(range.find("case.yaml:11:9: time: rtol = 0 is out of range; valid: (0, 1)"), std::string::npos) << range;
  EXPECT_NE(range.find("case.yaml:12:9: time: atol = -1e-09 is out of range; valid: (0, 1)"), std::string::npos)
      << range;
  EXPECT_NE(range.find("case.yaml:13:10: time: order = 9 is out of range; valid: [2, 8]"), std::string::npos) << range;

  const auto seven = errors_of(with_time("  dt: 1.0e-6\n  end: 1.0e-5\n  integrator: arkode\n  order: 7\n"));
  EXPECT_NE(seven.find("case.yaml:11:10: time: order = 7 has no ARKODE explicit table; valid: 2, 3, 4, 5, 6, 8"),
            std::string::npos)
      << seven;

  const auto type = errors_of(with_time("  dt: 1.0e-6\n  end: 1.0e-5\n  integrator: arkode\n  rtol: tight\n"));
  EXPECT_NE(type.find("case.yaml:11:9: time: rtol must be a finite number, got 'tight'"), std::string::npos) << type;

  // Tolerances without ARKODE are a mistake, not silently ignored.
  const auto verlet = errors_of(with_time("  dt: 1.0e-6\n  end: 1.0e-5\n  rtol: 1.0e-6\n"));
  EXPECT_NE(verlet.find("case.yaml:10:9: time: rtol applies to integrator: arkode; this case integrates with verlet"),
            std::string::npos)
      << verlet;
  const auto explicit_verlet =
      errors_of(with_time("  dt: 1.0e-6\n  end: 1.0e-5\n  integrator: verlet\n  order: 4\n"));
  EXPECT_NE(explicit_verlet.find("order applies to integrator: arkode"), std::string::npos) << explicit_verlet;
}

TEST(IntegratorKeys, SetOverridesSelectTheIntegrator) {
  auto c = parse_case(with_time("  dt: 1.0e-6\n  end: 1.0e-5\n"), "case.yaml",
                      {"time.integrator=arkode", "time.rtol=1e-4"});
  EXPECT_EQ(c.scene.integrator, sim::Integrator::Arkode);
  EXPECT_DOUBLE_EQ(c.scene.arkode.rtol, 1e-4);
  const auto m = errors_of(with_time("  dt: 1.0e-6\n  end: 1.0e-5\n"), {"time.integrator=euler"});
  EXPECT_NE(m.find("--set time.integrator=euler: time: integrator = 'euler' is not valid"), std::string::npos) << m;
}

TEST(IntegratorKeys, DocumentedWithTheOtherTimeKeys) {
  const auto* d = sim::find_effect_doc("time");
  ASSERT_NE(d, nullptr);
  ASSERT_NE(d->find("integrator"), nullptr);
  EXPECT_EQ(d->find("integrator")->choices, (std::vector<std::string>{"verlet", "arkode"}));
  for (const char* k : {"rtol", "atol", "order"}) EXPECT_NE(d->find(k), nullptr) << k;
}

}  // namespace
}  // namespace grains::io
