// Frozen grains (particles[].frozen, issue 25): held grains that are never
// integrated, keep their set's velocity and no spin, and push on the others
// as a wall does. Run as cases through the real stages:
//  - a sphere bouncing head-on off a frozen sphere (linear law, LAMMPS's
//    damping per unit m*) lasts t_c and leaves with e of m* = m, the free
//    sphere's own mass, as off a wall (with m* = m/2 both would differ by
//    more than 30 %); the frozen sphere does not move by a bit;
//  - a frozen set with a velocity moves rigidly at it and takes no spin
//    while a rough grain slides over it;
//  - frozen grains may overlap each other (their pairs are not listed) and
//    walls (they are not in the walls' near lists), not the grains that move;
//  - a frozen clump set is refused where it is written.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "tests/support/case_errors.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

constexpr double rho = 2500, R = 0.002, k = 2e4, gamma_rate = 4000;  // gamma_n / m*, 1/s
const double mass = rho * 4.0 / 3.0 * M_PI * R * R * R;

std::string linear_contact(double mu) {
  std::ostringstream o;
  o << "contact: {model: linear, tangential: " << (mu > 0 ? "linear" : "none")
    << ", linear: {stiffness: 2e4, damping_rate: 4000}}\n";
  return o.str();
}

// A set of one sphere at c, frozen or not.
std::string sphere(const std::string& name, const sim::Vec3& c, const sim::Vec3& v, bool frozen) {
  std::string s = single(name, "m", c, R, v);
  s.insert(s.rfind('}'), std::string(", frozen: ") + (frozen ? "true" : "false"));
  return s;
}

TEST(FrozenGrains, ABounceOffAFrozenSphereHasTheFreeSpheresMass) {
  const double ms = mass;  // m* of a contact with a frozen grain
  const double tc = M_PI / std::sqrt(k / ms - 0.25 * gamma_rate * gamma_rate);
  const double e = std::exp(-0.5 * gamma_rate * tc);
  const double v = 0.5, gap = 0.02 * R, dt = tc / 2000;
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [" << -4 * R << ", " << -2 * R << ", " << -2 * R << "], max: [" << 6 * R << ", " << 2 * R
    << ", " << 2 * R << "]}\n";
  y << "materials:\n" << material("m", rho, 1e8, 0.3, 0.9, 0) << linear_contact(0);
  y << "particles:\n" << sphere("base", sim::Vec3(0, 0, 0), sim::Vec3::Zero(), true)
    << sphere("ball", sim::Vec3(2 * R + gap, 0, 0), sim::Vec3(-v, 0, 0), false);
  y << "time: {dt: " << dt << ", end: " << 3 * tc + 4 * gap / v << "}\n";
  auto s = from_yaml(y.str());
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  const auto& p = sc.particles;
  const sim::Vec3 x0 = p.x[index_of(p, 0)];
  auto overlap = [&] { return 2 * R - (p.x[index_of(p, 1)] - p.x[index_of(p, 0)]).norm(); };
  double prev = overlap(), t_in = -1, t_out = -1;
  while (sc.clock.step < sc.clock.n_steps) {
    s.pipeline.step(sc);
    const double d = overlap();
    if (prev <= 0 && d > 0 && t_in < 0) t_in = sc.clock.time - dt * d / (d - prev);
    if (prev > 0 && d <= 0 && t_in >= 0 && t_out < 0) t_out = sc.clock.time - dt * d / (d - prev);
    prev = d;
  }
  ASSERT_GT(t_out, t_in);
  EXPECT_NEAR((t_out - t_in) / tc, 1.0, 0.005);
  EXPECT_NEAR(p.v[index_of(p, 1)][0] / v / e, 1.0, 0.005);
  // Held: not a bit of motion, though it bore the whole impact.
  EXPECT_EQ(p.x[index_of(p, 0)], x0);
  EXPECT_EQ(p.v[index_of(p, 0)], sim::Vec3::Zero());
  EXPECT_EQ(p.inv_mass[index_of(p, 0)], 0.0);
  EXPECT_DOUBLE_EQ(p.mass[index_of(p, 0)], mass) << "its mass stays (outputs, m* of its contacts)";
}

TEST(FrozenGrains, MoveRigidlyAtTheirVelocityWithoutSpin) {
  // A row of three frozen spheres gliding along +x, a rough sphere at rest in
  // the cradle of the first two: the row's push and friction carry it along
  // at the row's speed; the frozen ones keep their velocity exactly and take
  // no spin, though friction torques them.
  const sim::Vec3 u(0.05, 0, 0);
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.02, -0.01, -0.01], max: [0.04, 0.01, 0.02]}\n";
  y << "gravity: [0, 0, -9.81]\n";
  y << "materials:\n" << material("m", rho, 1e8, 0.3, 0.5, 0.5) << linear_contact(0.5);
  y << "particles:\n";
  for (int j = 0; j < 3; ++j) y << sphere("row" + std::to_string(j), sim::Vec3(2 * R * j, 0, 0), u, true);
  y << sphere("rider", sim::Vec3(R, 0, std::sqrt(3.0) * R + 1e-7), sim::Vec3::Zero(), false);
  y << "time: {dt: 2e-6, end: 0.1}\n";
  auto s = from_yaml(y.str());
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  const auto& p = sc.particles;
  std::vector<sim::Vec3> x0;
  for (int j = 0; j < 3; ++j) x0.push_back(p.x[index_of(p, j)]);
  while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
  const double t = sc.clock.time;
  for (int j = 0; j < 3; ++j) {
    const auto i = index_of(p, j);
    EXPECT_EQ(p.v[i], u) << "frozen " << j;
    EXPECT_EQ(p.omega[i], sim::Vec3::Zero()) << "frozen " << j;
    EXPECT_NEAR((p.x[i] - x0[static_cast<std::size_t>(j)] - u * t).norm(), 0.0, 1e-12) << "frozen " << j;
  }
  const auto r = index_of(p, 3);
  EXPECT_NEAR(p.v[r][0], u[0], 0.05 * u[0]) << "carried along";
  EXPECT_NEAR(p.x[r][0] - (x0[0][0] + u[0] * t), R, 0.02 * R) << "in its cradle";
  EXPECT_NEAR(p.x[r][2], std::sqrt(3.0) * R, 0.01 * R) << "in its cradle";
}

TEST(FrozenGrains, MayOverlapEachOtherAndWallsButAreNotListed) {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.01, -0.01, -0.01], max: [0.02, 0.01, 0.02]}\n";
  y << "materials:\n" << material("m", rho, 1e8, 0.3, 0.5, 0.5) << linear_contact(0.5);
  y << "walls:\n  - {type: plane, point: [0, 0, " << -0.5 * R << "], normal: [0, 0, 1], material: m}\n";
  y << "particles:\n"
    << sphere("a", sim::Vec3(0, 0, 0), sim::Vec3::Zero(), true)
    << sphere("b", sim::Vec3(R, 0, 0), sim::Vec3::Zero(), true)  // half a diameter into a
    << sphere("free", sim::Vec3(0.5 * R, 0, 2.05 * R), sim::Vec3::Zero(), false);
  y << "time: {dt: 1e-6, end: 1e-5}\n";
  auto s = from_yaml(y.str());
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
  const auto& p = sc.particles;
  const auto& nl = sc.neighbors;
  const auto a = index_of(p, 0), b = index_of(p, 1), f = index_of(p, 2);
  bool ab = false, free_listed = false;
  for (std::size_t i = 0; i + 1 < nl.row_start.size(); ++i)
    for (auto q = nl.row_start[i]; q < nl.row_start[i + 1]; ++q) {
      const std::size_t j = nl.partner[q];
      ab = ab || (i == a && j == b) || (i == b && j == a);
      free_listed = free_listed || i == f || j == f;
    }
  EXPECT_FALSE(ab) << "two frozen grains are never paired";
  EXPECT_TRUE(free_listed) << "a free grain within reach of them is";
  ASSERT_EQ(nl.wall_near.size(), 1u);
  for (const auto i : nl.wall_near[0]) EXPECT_EQ(i, f) << "only the free grain may touch the wall";
  EXPECT_EQ(p.x[a], sim::Vec3(0, 0, 0));
  EXPECT_EQ(p.x[b], sim::Vec3(R, 0, 0));
}

TEST(FrozenGrains, OverlappingTheGrainsThatMoveIsALocatedError) {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.01, -0.01, -0.01], max: [0.02, 0.01, 0.02]}\n";
  y << "materials:\n" << material("m", rho, 1e8, 0.3, 0.5, 0.5);
  y << "particles:\n"
    << sphere("base", sim::Vec3(0, 0, 0), sim::Vec3::Zero(), true)
    << sphere("free", sim::Vec3(R, 0, 0), sim::Vec3::Zero(), false);
  y << "time: {dt: 1e-6, end: 1e-5}\n";
  const std::string e = errors_of(y.str());
  EXPECT_NE(e.find("case.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("initial particles overlap"), std::string::npos) << e;
  EXPECT_NE(e.find("frozen grains may overlap each other, not the grains that move"), std::string::npos) << e;
}

TEST(FrozenGrains, AFrozenClumpSetIsRefusedWhereItIsWritten) {
  const std::string y =
      "domain: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}\n"
      "materials: [{name: m, density: 2500, youngs_modulus: 1e8, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}]\n"
      "particles:\n"
      "  - {name: c, material: m, radius: 0.005, count: 2, frozen: true,\n"
      "     shape: {type: clump, file: missing.clump},\n"
      "     placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}}\n"
      "time: {dt: 1e-6, end: 1e-5}\n";
  const std::string e = errors_of(y);
  EXPECT_NE(e.find("case.yaml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("frozen clumps are not supported"), std::string::npos) << e;
}

}  // namespace
}  // namespace grains::test
