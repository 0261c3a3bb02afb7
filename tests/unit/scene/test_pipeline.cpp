// The pipeline is assembled from the scene: absent effects have no stage,
// no law slot and no per-particle field.
#include <gtest/gtest.h>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"

namespace grains::io {
namespace {

std::string base(double friction, double rolling, const std::string& extra) {
  return R"(domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
materials:
  - {name: a, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, friction: )" +
         std::to_string(friction) + ", rolling_friction: " + std::to_string(rolling) + R"(}
particles:
  - {material: a, radius: 0.0005, count: 20, placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}}
time: {dt: 1.0e-6, end: 1.0e-5}
)" + extra;
}

TEST(Pipeline, FrictionlessWalllessSceneHasOnlyWhatItNeeds) {
  auto s = make_simulation(parse_case(base(0, 0, ""), "t.yaml"));
  const std::vector<std::string> stages{
      "drift: verlet.kick_drift+force_start", "neighbor: neighbor.verlet_list(skin trigger)",
      "force: force.clear(owned: in the drift)",
      "force: force.pair_contacts<hertz+tangential:none+rolling:none+cohesion:none>", "kick: verlet.kick"};
  EXPECT_EQ(s.pipeline.stage_names(), stages);
  const std::vector<std::string> fields{"id",   "position", "velocity", "force", "radius",
                                        "mass", "inv_mass", "material", "shape"};
  EXPECT_EQ(s.scene.particles.field_names(), fields);
  EXPECT_EQ(s.scene.neighbors.history_size(), 0);
  EXPECT_TRUE(s.scene.particles.omega.empty());
  EXPECT_TRUE(s.scene.particles.wall_history.empty());
}

TEST(Pipeline, FrictionGravityAndWallsAddTheirStagesAndFields) {
  auto s = make_simulation(parse_case(base(0.5, 0, R"(gravity: [0, 0, -9.81]
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: a}
  - {type: cylinder, base: [0.005, 0.005, 0], radius: 0.005, height: 0.01, material: a}
)"),
                                      "t.yaml"));
  const std::vector<std::string> stages{
      "drift: verlet.kick_drift+rotation+force_start",
      "neighbor: neighbor.verlet_list(skin trigger)",
      "force: force.clear+torque+gravity(owned: in the drift)",
      "force: force.pair_contacts<hertz+tangential:mindlin+rolling:none+cohesion:none>",
      "force: force.walls<hertz+tangential:mindlin+rolling:none+cohesion:none>",
      "kick: verlet.kick+rotation"};
  EXPECT_EQ(s.pipeline.stage_names(), stages);
  EXPECT_EQ(s.scene.neighbors.history_size(), 3);
  EXPECT_EQ(s.scene.particles.wall_history_size(), 6);  // 2 walls x 3
  EXPECT_EQ(s.scene.particles.omega.size(), s.scene.particles.size());
}

// The drift starts the owned particles' forces (F = m g, T = 0) in its pass
// and the clear then skips them; a force phase without a drift before it
// (done not set) clears them itself.
TEST(Pipeline, DriftStartsTheForcesAndTheClearCoversAForcePhaseWithoutIt) {
  auto s = make_simulation(parse_case(base(0.5, 0, "gravity: [0, 0, -9.81]\n"), "t.yaml"));
  auto& p = s.scene.particles;
  const auto& stages = s.pipeline.stages();
  ASSERT_EQ(stages[0]->name(), "verlet.kick_drift+rotation+force_start");
  ASSERT_EQ(stages[2]->name(), "force.clear+torque+gravity(owned: in the drift)");
  auto scramble = [&p] {
    for (std::size_t i = 0; i < p.size(); ++i) p.f[i] = sim::Vec3(1, 2, 3), p.torque[i] = sim::Vec3(4, 5, 6);
  };
  auto started = [&p, &s] {
    for (std::size_t i = 0; i < p.n_owned(); ++i)
      if (p.f[i] != sim::Vec3(p.mass[i] * s.scene.gravity) || p.torque[i] != sim::Vec3::Zero()) return false;
    return true;
  };
  ASSERT_GT(p.n_owned(), 0u);
  scramble();
  stages[2]->run(s.scene);  // no drift before: the clear does it all
  EXPECT_TRUE(started());
  scramble();
  stages[0]->run(s.scene);  // the drift starts them
  EXPECT_TRUE(started());
  scramble();
  stages[2]->run(s.scene);  // the drift did it: owned particles left alone
  EXPECT_EQ(p.f[0], sim::Vec3(1, 2, 3));
  stages[2]->run(s.scene);  // a second force phase: the clear again
  EXPECT_TRUE(started());
  // Radius growth changes masses in the drift phase: the clear keeps its pass.
  auto g = make_simulation(parse_case(
      base(0.5, 0, "gravity: [0, 0, -9.81]\nradius_growth: {rate: 0.1, target_overlap: 1.0e-4}\n"), "t.yaml"));
  EXPECT_EQ(g.pipeline.stages()[0]->name(), "verlet.kick_drift+rotation");
}

TEST(Pipeline, RollingAndCohesionSlots) {
  auto s = make_simulation(parse_case(base(0.5, 0.1, "contact: {cohesion: sjkr}\n"), "t.yaml"));
  EXPECT_EQ(s.pipeline.stage_names()[3],
            "force: force.pair_contacts<hertz+tangential:mindlin+rolling:epsd+cohesion:sjkr>");
  EXPECT_EQ(s.scene.neighbors.history_size(), 6);
  auto n = make_simulation(parse_case(base(0.5, 0.1, "contact: {tangential: none, rolling: none}\n"), "t.yaml"));
  EXPECT_EQ(n.pipeline.stage_names()[3],
            "force: force.pair_contacts<hertz+tangential:none+rolling:none+cohesion:none>");
}

TEST(Pipeline, OutputStagesExistOnlyWhenAsked) {
  auto s = make_simulation(parse_case(base(0, 0, "output: {vtk: false, progress: false}\n"), "t.yaml"));
  RunOptions o;
  add_output_stages(s, o);
  for (const auto& n : s.pipeline.stage_names()) EXPECT_EQ(n.find("output.vtk"), std::string::npos) << n;
}

}  // namespace
}  // namespace grains::io
