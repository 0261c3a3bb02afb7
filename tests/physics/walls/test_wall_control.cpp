// Controlled walls (walls[].control, issue 25): servo walls holding a stress
// or a force, and strain-controlled planes. Real scenes through the real
// stages:
//  - an oedometer (a bed of frictional spheres, no gravity, in a box whose
//    lid holds 5 kPa): the lid settles at the target, and the other walls,
//    which measure the load independently, bear the same (the floor most of
//    it, the side walls the rest by friction);
//  - an isotropic compression, all six walls servo-controlled: each wall's
//    area is the product of the other two gaps as they close, and all hold
//    the target;
//  - a mesh piston holding a force, borne by the other walls;
//  - a strain-controlled lid: the sample's length shrinks (or grows) by the
//    factor (1 - rate dt) per step, exactly;
//  - bad control blocks: located errors.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "sim/walls/wall_control_stage.hpp"
#include "tests/support/case_errors.hpp"
#include "tests/support/sim_helpers.hpp"
#include "tests/support/temp_dir.hpp"

namespace grains::test {
namespace {

using sim::PlaneWall;

// A bed of `count` spheres (r 0.4-0.5 mm, mu 0.3) in a 10 x 10 x 20 mm
// region, no gravity, walls of friction 0, then `walls` (YAML list items).
std::string box_case(int count, const std::string& walls, double end, const std::string& extra = "") {
  std::ostringstream y;
  y << "domain: {min: [-0.001, -0.001, -0.001], max: [0.011, 0.011, 0.021]}\n"
       "gravity: [0, 0, 0]\n"
       "materials:\n"
    << material("grain", 2500, 1e7, 0.3, 0.5, 0.3) << material("wall", 2500, 1e7, 0.3, 0.5, 0.0)
    << "particles:\n"
       "  - {name: bed, material: grain, radius: {distribution: uniform, min: 0.0004, max: 0.0005}, count: "
    << count
    << ", placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.02]}, seed: 4}}\n"
       "walls:\n"
    << walls << "time: {dt_rayleigh: 0.2, end: " << end << "}\n"
    << extra;
  return y.str();
}

std::string plane(const std::string& name, const std::string& point, const std::string& normal,
                  const std::string& control = "") {
  return "  - {type: plane, name: " + name + ", point: " + point + ", normal: " + normal + ", material: wall" +
         (control.empty() ? "" : ", control: " + control) + "}\n";
}

std::string side_walls(const std::string& control = "") {
  return plane("x0", "[0, 0, 0]", "[1, 0, 0]", control) + plane("x1", "[0.01, 0, 0]", "[-1, 0, 0]", control) +
         plane("y0", "[0, 0, 0]", "[0, 1, 0]", control) + plane("y1", "[0, 0.01, 0]", "[0, -1, 0]", control);
}

// Runs to the end; returns the mean over the last `tail` steps of f().
template <class F>
double run_and_average(io::Simulation& s, std::int64_t tail, F&& f) {
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  double sum = 0;
  std::int64_t n = 0;
  while (sc.clock.step < sc.clock.n_steps) {
    s.pipeline.step(sc);
    if (sc.clock.n_steps - sc.clock.step < tail) sum += f(), ++n;
  }
  return sum / static_cast<double>(n);
}

const PlaneWall& wall(const io::Simulation& s, const std::string& name) {
  for (const auto& w : s.scene.walls.of<PlaneWall>())
    if (w.name == name) return w;
  throw std::runtime_error("no wall " + name);
}

TEST(ServoWalls, AnOedometerLidHoldsItsStressAndTheFloorBearsIt) {
  const double P = 5000, area = 1e-4;  // the box is 10 x 10 mm
  auto s = from_yaml(box_case(300,
                              side_walls() + plane("floor", "[0, 0, 0]", "[0, 0, 1]") +
                                  plane("lid", "[0, 0, 0.0205]", "[0, 0, -1]", "{stress: 5000, max_speed: 0.1}"),
                              0.4));
  // What the other walls bear along z: the floor, and the side walls by
  // friction (a Janssen effect); at rest, without gravity, it is the lid's load.
  double others = 0, floor_load = 0;
  const double lid = run_and_average(s, 2000, [&] {
    for (std::size_t k = 0; k < 5; ++k) others += s.scene.wall_loads[k].force.z() / 1999;
    floor_load += s.scene.wall_loads[4].force.z() / 1999;
    return wall(s, "lid").control.load;
  });
  const auto& c = wall(s, "lid").control;
  EXPECT_DOUBLE_EQ(c.area_now, area) << "the cross-section between the side walls";
  EXPECT_NEAR(lid / (P * area), 1.0, 1e-3);
  EXPECT_NEAR(-others / (P * area), 1.0, 2e-3) << "no gravity: the other walls bear what the lid puts on the bed";
  EXPECT_GT(-floor_load / (P * area), 0.9) << "most of it on the floor";
  EXPECT_LT(std::abs(c.speed), 1e-4) << "at rest once it holds the load";
  EXPECT_LT(wall(s, "lid").point.z(), 0.012) << "the loose fill was compressed";
}

TEST(ServoWalls, AllSixWallsOfAnIsotropicCompressionHoldTheTargetOnTheirCurrentAreas) {
  const std::string c = "{stress: 5000, max_speed: 0.05}";
  auto s = from_yaml(box_case(300,
                              side_walls(c) + plane("floor", "[0, 0, 0]", "[0, 0, 1]", c) +
                                  plane("lid", "[0, 0, 0.0205]", "[0, 0, -1]", c),
                              0.3));
  std::vector<double> sum(6, 0.0);
  (void)run_and_average(s, 2000, [&] {
    std::size_t k = 0;
    for (const auto& w : s.scene.walls.of<PlaneWall>()) sum[k++] += w.control.load / w.control.area_now;
    return 0.0;
  });
  for (double v : sum) EXPECT_NEAR(v / 1999 / 5000, 1.0, 2e-3);
  const auto gap = [&](const char* a, const char* b, int axis) {
    return wall(s, b).point[axis] - wall(s, a).point[axis];
  };
  const double lx = gap("x0", "x1", 0), ly = gap("y0", "y1", 1), lz = gap("floor", "lid", 2);
  EXPECT_LT(lx, 0.009) << "the side walls closed in too";
  EXPECT_DOUBLE_EQ(wall(s, "x0").control.area_now, ly * lz);
  EXPECT_DOUBLE_EQ(wall(s, "y1").control.area_now, lx * lz);
  EXPECT_DOUBLE_EQ(wall(s, "lid").control.area_now, lx * ly);
  // Solid fraction of a compressed loose fill of frictional spheres (a few
  // diameters across: the walls loosen it): between random loose and close.
  double vs = 0;
  for (std::size_t i = 0; i < s.scene.particles.n_owned(); ++i) vs += 4.0 / 3.0 * M_PI * std::pow(s.scene.particles.radius[i], 3);
  const double phi = vs / (lx * ly * lz);
  EXPECT_GT(phi, 0.5);
  EXPECT_LT(phi, 0.66);
}

TEST(ServoWalls, AMeshPistonHoldsAForce) {
  TempDir tmp("servo_mesh");
  const auto obj = tmp.path / "plate.obj";
  {
    std::ofstream o(obj);  // a 10 x 10 mm plate at z = 0.0205 (two triangles)
    o << "v 0 0 0.0205\nv 0.01 0 0.0205\nv 0.01 0.01 0.0205\nv 0 0.01 0.0205\nf 1 2 3\nf 1 3 4\n";
  }
  const double F = 0.3;
  auto s = from_yaml(box_case(300,
                              side_walls() + plane("floor", "[0, 0, 0]", "[0, 0, 1]") +
                                  "  - {type: mesh, name: piston, file: " + obj.string() +
                                  ", material: wall, control: {force: 0.3, direction: [0, 0, -1], max_speed: 0.1}}\n",
                              0.4));
  double others = 0;
  const double load = run_and_average(s, 2000, [&] {
    for (std::size_t k = 0; k < 5; ++k) others += s.scene.wall_loads[k].force.z() / 1999;
    return s.scene.walls.of<sim::MeshWall>()[0].control.load;
  });
  const auto& m = s.scene.walls.of<sim::MeshWall>()[0];
  EXPECT_NEAR(load / F, 1.0, 1e-3);
  EXPECT_NEAR(-others / F, 1.0, 2e-3) << "the floor and the side walls bear the piston's force";
  EXPECT_LT(m.offset.z(), -0.008) << "it came down onto the bed";
  EXPECT_DOUBLE_EQ(m.offset.z(), -m.control.travel) << "its offset is its travel along -z";
}

TEST(StrainRate, TheSamplesLengthChangesByOneMinusRateDtEachStep) {
  for (double rate : {2.0, -1.0}) {
    std::ostringstream c;
    c << "{strain_rate: " << rate << "}";
    auto s = from_yaml(box_case(20, plane("floor", "[0, 0, 0]", "[0, 0, 1]") +
                                        plane("lid", "[0, 0, 0.0205]", "[0, 0, -1]", c.str()),
                                0.02));
    auto& sc = s.scene;
    s.pipeline.initialize(sc);
    const double L0 = 0.0205, dt = sc.clock.dt;
    while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
    const double expect = L0 * std::pow(1 - rate * dt, static_cast<double>(sc.clock.step));
    EXPECT_NEAR(wall(s, "lid").point.z() / expect, 1.0, 1e-11) << "rate " << rate;
    EXPECT_NEAR(wall(s, "lid").point.z() / (L0 * std::exp(-rate * sc.clock.time)), 1.0, 1e-4) << "rate " << rate;
    EXPECT_EQ(wall(s, "lid").velocity, wall(s, "lid").control.speed * sim::Vec3(0, 0, -1));
  }
}

TEST(WallControlErrors, AreLocated) {
  auto with = [&](const std::string& lid, const std::string& extra = "") {
    return errors_of(box_case(10, side_walls() + plane("floor", "[0, 0, 0]", "[0, 0, 1]") + lid, 0.01, extra));
  };
  const std::string lid = "  - {type: plane, name: lid, point: [0, 0, 0.0205], normal: [0, 0, -1], material: wall, ";
  std::string e = with(lid + "control: {stress: -5000, max_speed: 0.05}}\n");
  EXPECT_NE(e.find("walls[5].control"), std::string::npos) << e;
  EXPECT_NE(e.find("must be compressive"), std::string::npos) << e;
  EXPECT_NE(e.find("-5000"), std::string::npos) << e;
  e = with(lid + "control: {force: 0, max_speed: 0.05}}\n");
  EXPECT_NE(e.find("force must be compressive"), std::string::npos) << e;
  e = with(lid + "control: {stress: 5000}}\n");
  EXPECT_NE(e.find("needs max_speed"), std::string::npos) << e;
  e = with(lid + "velocity: [0, 0, -0.1], control: {stress: 5000, max_speed: 0.05}}\n");
  EXPECT_NE(e.find("remove velocity"), std::string::npos) << e;
  e = with(lid + "control: {stress: 5000, strain_rate: 1, max_speed: 0.05}}\n");
  EXPECT_NE(e.find("exactly one of stress, force or strain_rate (2 given)"), std::string::npos) << e;
  e = with(lid + "control: {stress: 5000, max_speed: 0.05, direction: [0, 0, 1]}}\n");
  EXPECT_NE(e.find("moves along its normal"), std::string::npos) << e;
  e = with(lid + "control: {strain_rate: 0}}\n");
  EXPECT_NE(e.find("strain_rate must not be 0"), std::string::npos) << e;
  // No cross-section: without side walls the box is open along x and y.
  e = errors_of(box_case(10, plane("floor", "[0, 0, 0]", "[0, 0, 1]") + lid + "control: {stress: 5000, max_speed: 0.05}}\n", 0.01));
  EXPECT_NE(e.find("case.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("walls 'lid' control"), std::string::npos) << e;
  EXPECT_NE(e.find("along x the domain is not periodic"), std::string::npos) << e;
  EXPECT_NE(e.find("give area"), std::string::npos) << e;
  // ...which an area settles.
  EXPECT_NO_THROW(from_yaml(box_case(10, plane("floor", "[0, 0, 0]", "[0, 0, 1]") + lid +
                                             "control: {stress: 5000, area: 1e-4, max_speed: 0.05}}\n",
                                     0.01)));
  // A strain rate with no plane facing it.
  e = errors_of(box_case(10, side_walls() + lid + "control: {strain_rate: 1}}\n", 0.01));
  EXPECT_NE(e.find("no infinite plane faces this one"), std::string::npos) << e;
  // ARKODE.
  std::string ark = box_case(10, side_walls() + plane("floor", "[0, 0, 0]", "[0, 0, 1]") + lid +
                                     "control: {stress: 5000, max_speed: 0.05}}\n",
                             0.01);
  ark.replace(ark.find("time: {"), 7, "time: {integrator: arkode, ");
  e = errors_of(ark);
  EXPECT_NE(e.find("use time.integrator: verlet"), std::string::npos) << e;
  // A mesh needs its direction.
  e = with("  - {type: mesh, name: m, file: nowhere.obj, material: wall, control: {force: 1, max_speed: 0.1}}\n");
  EXPECT_NE(e.find("give direction"), std::string::npos) << e;
  // A cylinder takes no control.
  e = with("  - {type: cylinder, name: c, base: [0.005, 0.005, 0], radius: 0.005, height: 0.02, material: wall, "
           "control: {force: 1, max_speed: 0.1}}\n");
  EXPECT_NE(e.find("control"), std::string::npos) << e;
}

}  // namespace
}  // namespace grains::test
