// Finite planes (contact/plane.hpp Annulus, PlaneWall::hole_radius/radius):
// the geometry of the nearest point and the contact, a sphere resting on the
// rim of a hole smaller than itself, passing through a larger one, touching
// the underside; an ellipsoid lying across a hole on two rim contacts, passing
// it upright, resting on a face; case keys and their errors; the walls file read back by
// postprocess; the mass output (output.mass) of a small draining silo.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "contact/plane.hpp"
#include "io/output/mass_output.hpp"
#include "postprocess/walls.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

using contact::Annulus;
using contact::ContactGeometry;
using sim::Vec3;
namespace fs = std::filesystem;

const Annulus kHoled{Vec3(0, 0, 0), Vec3(0, 0, 1), 0.002, std::numeric_limits<double>::infinity()};

TEST(FinitePlaneGeometry, FaceContactOnBothSides) {
  ContactGeometry g;
  // Above the solid part: the face normal, overlap r - height.
  ASSERT_TRUE(contact::sphere_annulus(Vec3(0.005, 0, 0.0009), 0.001, kHoled, g));
  EXPECT_NEAR(g.overlap, 0.0001, 1e-15);
  EXPECT_NEAR((g.normal - Vec3(0, 0, 1)).norm(), 0, 1e-15);
  EXPECT_NEAR((g.point - Vec3(0.005, 0, 0)).norm(), 0, 1e-15);
  EXPECT_EQ(g.radius, 0.001);
  // Below (the plate has two faces): pushed down.
  ASSERT_TRUE(contact::sphere_annulus(Vec3(0, 0.005, -0.0009), 0.001, kHoled, g));
  EXPECT_NEAR(g.overlap, 0.0001, 1e-15);
  EXPECT_NEAR((g.normal - Vec3(0, 0, -1)).norm(), 0, 1e-15);
  // Out of reach.
  EXPECT_FALSE(contact::sphere_annulus(Vec3(0.005, 0, 0.0011), 0.001, kHoled, g));
  EXPECT_FALSE(contact::sphere_annulus(Vec3(0.005, 0, -0.0011), 0.001, kHoled, g));
}

TEST(FinitePlaneGeometry, RimOfTheHole) {
  ContactGeometry g;
  // Centre in the plane of the hole, 0.5 mm from its rim: the rim touches
  // along the radial direction.
  ASSERT_TRUE(contact::sphere_annulus(Vec3(0, 0.0015, 0), 0.001, kHoled, g));
  EXPECT_NEAR(g.overlap, 0.0005, 1e-15);
  EXPECT_NEAR((g.normal - Vec3(0, -1, 0)).norm(), 0, 1e-12);
  EXPECT_NEAR((g.point - Vec3(0, 0.002, 0)).norm(), 0, 1e-15);
  // Above the hole, 45 degrees from the rim.
  const Vec3 x(0.002 - 0.0006, 0, 0.0006);
  ASSERT_TRUE(contact::sphere_annulus(x, 0.001, kHoled, g));
  EXPECT_NEAR(g.overlap, 0.001 - 0.0006 * std::sqrt(2.0), 1e-15);
  EXPECT_NEAR((g.normal - Vec3(-1, 0, 1).normalized()).norm(), 0, 1e-12);
  // A small sphere in the middle of the hole touches nothing.
  EXPECT_FALSE(contact::sphere_annulus(Vec3(0, 0, 0), 0.0015, kHoled, g));
  // On the axis of a hole smaller than the sphere: the normal is along the
  // axis, the overlap r - sqrt(a^2 + h^2).
  const Annulus small{Vec3(0, 0, 0), Vec3(0, 0, 1), 0.0006, std::numeric_limits<double>::infinity()};
  ASSERT_TRUE(contact::sphere_annulus(Vec3(0, 0, 0.0005), 0.001, small, g));
  EXPECT_NEAR(g.overlap, 0.001 - std::hypot(0.0006, 0.0005), 1e-15);
  EXPECT_NEAR(g.normal.z(), 0.0005 / std::hypot(0.0006, 0.0005), 1e-12);
}

TEST(FinitePlaneGeometry, OuterRimOfADisc) {
  const Annulus disc{Vec3(1, 2, 3), Vec3(1, 0, 0), 0, 0.01};
  ContactGeometry g;
  // Beyond the outer rim, level with the disc: the rim touches radially.
  ASSERT_TRUE(contact::sphere_annulus(Vec3(1, 2.0105, 3), 0.001, disc, g));
  EXPECT_NEAR(g.overlap, 0.0005, 1e-12);
  EXPECT_NEAR((g.normal - Vec3(0, 1, 0)).norm(), 0, 1e-9);
  EXPECT_FALSE(contact::sphere_annulus(Vec3(1, 2.0115, 3), 0.001, disc, g));
  // Over the disc's face (a full disc: no hole at the centre).
  ASSERT_TRUE(contact::sphere_annulus(Vec3(1.0005, 2, 3), 0.001, disc, g));
  EXPECT_NEAR((g.normal - Vec3(1, 0, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR(g.overlap, 0.0005, 1e-15);
}

// One sphere of radius r dropped under gravity onto a horizontal plane with a
// hole of radius a centred below it (frictionless, strongly damped).
struct Drop {
  double final_z = 0;
  std::int64_t lost = 0;
};

void run_all(io::Simulation& s) {
  s.pipeline.initialize(s.scene);
  while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
}
Drop drop_on_hole(double r, double a, double x0, double z0, double end) {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.02, -0.02, -0.01], max: [0.02, 0.02, 0.02]}\ngravity: [0, 0, -9.81]\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.3, 0.0)
    << "particles:\n" << single("ball", "m", Vec3(x0, 0, z0), r, Vec3(0, 0, 0))
    << "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], hole_radius: " << a << ", material: m}\n"
    << "time: {dt_rayleigh: 0.2, end: " << end << "}\n";
  auto s = from_yaml(y.str());
  run_all(s);
  Drop d;
  d.lost = s.scene.lost_particles;
  if (s.scene.particles.n_owned() == 1) d.final_z = s.scene.particles.x[0].z();
  return d;
}

TEST(FinitePlaneWall, SphereLargerThanTheHoleRestsOnItsRim) {
  // Equilibrium on the rim circle of radius a: the centre sits sqrt(r^2 - a^2)
  // above the plane, less the elastic overlap (mg / rim contact, well below
  // 1e-3 r here).
  const double r = 0.001, a = 0.0006;
  const auto d = drop_on_hole(r, a, 0, 0.0012, 0.08);
  EXPECT_EQ(d.lost, 0);
  EXPECT_NEAR(d.final_z, std::sqrt(r * r - a * a), 2e-3 * r);
}

TEST(FinitePlaneWall, SphereBesideTheHoleRestsOnTheFace) {
  const double r = 0.001, a = 0.0006;
  const auto d = drop_on_hole(r, a, 0.004, 0.0012, 0.08);
  EXPECT_NEAR(d.final_z, r, 2e-3 * r);
}

TEST(FinitePlaneWall, SphereSmallerThanTheHoleFallsThroughAndLeavesTheDomain) {
  // Falls 10 mm below the plane (0.06 s) and is removed at the domain's floor.
  const auto d = drop_on_hole(0.001, 0.0015, 0, 0.002, 0.09);
  EXPECT_EQ(d.lost, 1);
}

TEST(FinitePlaneWall, UndersideOfADiscStopsARisingSphere) {
  // A disc of radius 5 mm, no gravity: a sphere moving up at 0.1 m/s below it
  // bounces off its underside (e = 1 against the infinitely heavy wall).
  const std::string yaml = R"(
domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e8, poisson_ratio: 0.3, restitution: 1.0, friction: 0}
particles:
  - {material: m, radius: 0.001, count: 1, velocity: [0, 0, 0.1], placement: {type: lattice, region: {min: [0.001, -0.001, -0.0045], max: [0.0035, 0.0015, -0.002]}}}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], radius: 0.005, material: m}
time: {dt_rayleigh: 0.05, end: 0.05}
)";
  auto s = from_yaml(yaml);
  run_all(s);
  ASSERT_EQ(s.scene.particles.n_owned(), 1u);
  EXPECT_NEAR(s.scene.particles.v[0].z(), -0.1, 0.1 * 0.005);
  EXPECT_LT(s.scene.particles.x[0].z(), -0.001);
}

std::string case_errors(const std::string& yaml) {
  try {
    (void)from_yaml(yaml);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

TEST(FinitePlaneWall, CaseKeysAreCheckedWithLocations) {
  const std::string head = R"(domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, friction: 0.5}
particles:
  - {material: m, radius: 0.0005, count: 5, placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.005, 0.005, 0.005]}}}
time: {dt_rayleigh: 0.2, end: 0.001}
walls:
)";
  auto ok = from_yaml(head + "  - {type: plane, point: [0, 0, 0], normal: [0, 0, 2], hole_radius: 0.001, radius: 0.008, material: m}\n");
  ASSERT_EQ(ok.scene.walls.of<sim::PlaneWall>().size(), 1u);
  const auto& w = ok.scene.walls.of<sim::PlaneWall>()[0];
  EXPECT_TRUE(w.finite());
  EXPECT_EQ(w.hole_radius, 0.001);
  EXPECT_EQ(w.radius, 0.008);
  EXPECT_NEAR(w.normal.z(), 1.0, 1e-15);
  EXPECT_FALSE(from_yaml(head + "  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}\n")
                   .scene.walls.of<sim::PlaneWall>()[0]
                   .finite());
  const auto e1 = case_errors(head + "  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], hole_radius: 0.003, radius: 0.002, material: m}\n");
  EXPECT_NE(e1.find("test.yaml:8:"), std::string::npos) << e1;
  EXPECT_NE(e1.find("radius must be larger than hole_radius"), std::string::npos) << e1;
  const auto e2 = case_errors(head + "  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], hole_radius: -0.001, material: m}\n");
  EXPECT_NE(e2.find("hole_radius = -0.001 m is out of range"), std::string::npos) << e2;
  // With ellipsoids a finite plane keeps two history slots per particle (a
  // grain can touch an annulus at two places), an infinite one keeps one.
  std::string ell = head + "  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], hole_radius: 0.001, material: m}\n" +
                    "  - {type: plane, point: [0, 0, -0.005], normal: [0, 0, 1], material: m}\n";
  ell.replace(ell.find("radius: 0.0005,"), 15, "radius: 0.0005, shape: {type: ellipsoid, aspect_ratio: 1.5},");
  auto e = from_yaml(ell);
  ASSERT_EQ(e.scene.walls.of<sim::PlaneWall>().size(), 2u);
  EXPECT_EQ(e.scene.walls.of<sim::PlaneWall>()[0].history_slots, 2);
  EXPECT_EQ(e.scene.walls.of<sim::PlaneWall>()[1].history_slot, 2);
  EXPECT_EQ(e.scene.walls.of<sim::PlaneWall>()[1].history_slots, 1);
  EXPECT_EQ(ok.scene.walls.of<sim::PlaneWall>()[0].history_slots, 1);
}

// One prolate spheroid, semi-axes (2, 0.5, 0.5) mm, dropped from rest onto a
// horizontal plane with a hole of radius a centred below it, with friction.
struct EllipsoidDrop {
  sim::Vec3 x{0, 0, 0}, v{0, 0, 0}, axis{0, 0, 0};  // final centre, velocity, long axis
  std::int64_t lost = 0;
  int two_contact_steps = 0;  // steps with both of the wall's slots holding history
  int slot_jumps = 0;         // steps where the history moved from one slot to the other, alone
  int rim_steps = 0;          // steps with the centre over the hole and a contact
};

EllipsoidDrop drop_ellipsoid(const std::string& orientation, double a, sim::Vec3 x0, double end, double mu_r = 0,
                             sim::Vec3 v0 = sim::Vec3::Zero()) {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.02, -0.02, -0.01], max: [0.02, 0.02, 0.02]}\ngravity: [0, 0, -9.81]\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.3, 0.3, mu_r)
    << "particles:\n" << single("needle", "m", x0, 0.002, v0)
    << "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], hole_radius: " << a << ", material: m}\n"
    << "time: {dt_rayleigh: 0.2, end: " << end << "}\n";
  std::string text = y.str();
  text.replace(text.find("radius: 0.002,"), 14,
               "radius: 0.002, shape: {type: ellipsoid, semi_axes: [4, 1, 1], orientation: " + orientation + "},");
  auto s = from_yaml(text);
  s.pipeline.initialize(s.scene);
  EllipsoidDrop d;
  auto& p = s.scene.particles;
  int last_mask = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    if (p.n_owned() == 1 && p.wall_history_size() > 0) {
      const int H = p.wall_history_size() / 2;
      auto held = [&](int k) {
        for (int j = 0; j < H; ++j)
          if (p.wall_history[static_cast<std::size_t>(k * H + j)] != 0.0) return true;
        return false;
      };
      d.two_contact_steps += held(0) && held(1);
      const int mask = held(0) + 2 * held(1);
      d.slot_jumps += (mask == 1 && last_mask == 2) || (mask == 2 && last_mask == 1);
      d.rim_steps += mask != 0 && std::hypot(p.x[0].x(), p.x[0].y()) < a;
      last_mask = mask;
    }
  }
  d.lost = s.scene.lost_particles;
  if (p.n_owned() == 1) {
    d.x = p.x[0];
    d.v = p.v[0];
    d.axis = p.orientation[0].toRotationMatrix().col(0);
  }
  return d;
}

TEST(FinitePlaneWall, EllipsoidLyingAcrossTheHoleRestsOnBothSidesOfItsRim) {
  // Lying across a hole of radius 1 mm: the rim cuts the body where its
  // lower surface is b sqrt(1 - (1/2)^2) below the axis, so it comes to rest
  // with its centre 0.433 mm above the sheet (less the elastic overlap),
  // level, held at two rim points, each with its own tangential history.
  const auto d = drop_ellipsoid("[1, 0, 0, 0]", 0.001, Vec3(0, 0, 0.0006), 0.1);
  EXPECT_EQ(d.lost, 0);
  EXPECT_NEAR(d.x.z(), 0.0005 * std::sqrt(0.75), 2e-3 * 0.0005);
  EXPECT_NEAR(d.x.x(), 0.0, 1e-6);
  EXPECT_LT(d.v.norm(), 1e-4);
  EXPECT_LT(std::abs(d.axis.z()), 1e-3);
  EXPECT_GT(d.two_contact_steps, 1000);
}

TEST(FinitePlaneWall, EllipsoidLyingOffCentreAcrossTheHoleComesToRest) {
  // Dropped 0.3 mm off the hole's centre along its axis and 0.2 mm across:
  // the rim holds it at two unequal points. It rocks in the hole like a
  // cylinder in a cradle (rolling over the rim without slip dissipates
  // nothing), so rolling resistance brings it to rest, nearly level.
  const auto d = drop_ellipsoid("[1, 0, 0, 0]", 0.001, Vec3(0.0003, 0.0002, 0.0006), 0.15, 0.1);
  EXPECT_EQ(d.lost, 0);
  EXPECT_LT(d.v.norm(), 1e-4);
  EXPECT_GT(d.x.z(), 0.0003);
  EXPECT_LT(std::abs(d.axis.z()), 0.05);
  EXPECT_GT(d.two_contact_steps, 1000);
}

TEST(FinitePlaneWall, EllipsoidSlidingIntoTheHoleKeepsItsTangentialHistory) {
  // Lying on the plate beside a hole of radius 1.5 mm and sliding towards
  // it at 0.25 m/s with friction: its one contact passes from the face to
  // the rim (and it tips into the hole); the tangential history stays in
  // its slot throughout, never jumping to the other one alone.
  const auto d = drop_ellipsoid("[1, 0, 0, 0]", 0.0015, Vec3(0.0045, 0, 0.0005), 0.06, 0, Vec3(-0.25, 0, 0));
  EXPECT_GT(d.rim_steps, 50) << "never reached the rim";
  EXPECT_EQ(d.slot_jumps, 0);
}

TEST(FinitePlaneWall, EllipsoidStandingUpFallsThroughTheHole) {
  // The same body upright (long axis along z, rotated about y) passes a hole
  // of radius 0.7 mm it could not pass lying down, and leaves the domain.
  const auto d = drop_ellipsoid("[0.70710678118654757, 0, 0.70710678118654746, 0]", 0.0007, Vec3(0, 0, 0.0025), 0.12);
  EXPECT_EQ(d.lost, 1);
}

TEST(FinitePlaneWall, EllipsoidBesideTheHoleRestsOnTheFaceAsOnAPlane) {
  const auto d = drop_ellipsoid("[1, 0, 0, 0]", 0.001, Vec3(0.005, 0.003, 0.0006), 0.08);
  EXPECT_EQ(d.lost, 0);
  EXPECT_NEAR(d.x.z(), 0.0005, 2e-3 * 0.0005);
  EXPECT_EQ(d.two_contact_steps, 0);
}

// A tiny silo: grains of radius 0.5 mm (`particles`: the set's count and
// shape keys) filled into a cylinder of radius 5 mm on a plane with a hole of
// radius 2.5 mm, run to `end` s; `extra` lines are appended (e.g. output).
std::string tiny_silo(const std::string& particles, double end, const std::string& extra = "") {
  std::ostringstream y;
  y << "domain: {min: [-0.006, -0.006, -0.003], max: [0.006, 0.006, 0.02]}\ngravity: [0, 0, -9.81]\nmaterials:\n"
    << "  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.3}\n"
    << "particles:\n  - {material: m, radius: 0.0005, " << particles
    << ", placement: {type: random_fill, region: {min: [-0.0035, -0.0035, 0.0006], max: [0.0035, 0.0035, 0.02]}}}\n"
    << "walls:\n"
    << "  - {type: plane, name: bottom, point: [0, 0, 0], normal: [0, 0, 1], hole_radius: 0.0025, material: m}\n"
    << "  - {type: cylinder, base: [0, 0, -0.001], radius: 0.005, height: 0.021, material: m}\n"
    << "time: {dt_rayleigh: 0.2, end: " << end << "}\n"
    << extra;
  return y.str();
}

TEST(FinitePlaneWall, SpheroidsDrainThroughTheOrificeAndNeverThroughThePlate) {
  // A tiny silo of 100 prolate spheroids (aspect ratio 2, random
  // orientations): they drain through a hole of radius 2.5 equivalent
  // diameters, and no spheroid centre ever lies below the plate outside the
  // hole by more than its smallest semi-axis (it would have gone through
  // the face or the rim).
  auto s = from_yaml(tiny_silo("count: 100, shape: {type: ellipsoid, aspect_ratio: 2}", 0.15));
  s.pipeline.initialize(s.scene);
  const auto& p = s.scene.particles;
  int leaks = 0, rim_steps = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    for (std::size_t i = 0; i < p.n_owned(); ++i) {
      const double rho = std::hypot(p.x[i].x(), p.x[i].y());
      const double b = p.semi_axes[i].minCoeff();
      if (p.x[i].z() < -b && rho > 0.0025 + b) ++leaks;
      if (p.x[i].z() > -p.radius[i] && p.x[i].z() < p.radius[i] && std::abs(rho - 0.0025) < p.radius[i]) ++rim_steps;
    }
  }
  EXPECT_EQ(leaks, 0);
  EXPECT_GT(rim_steps, 1000) << "no spheroid came near the rim";
  EXPECT_GT(s.scene.lost_particles, 20) << "the silo does not drain";
  EXPECT_LT(s.scene.lost_particles, 100);
}

TEST(FinitePlaneWall, WallsFileReadsBackAndMassOutputFollowsTheDischarge) {
  // A tiny silo: a cylinder on a plane with a hole of radius 2.5 d; the mass
  // above the plane falls as the grains drain, the grains that left are
  // counted as lost, and the walls file reads back as a plane with a hole.
  auto s = from_yaml(tiny_silo("count: 200", 0.12,
                               "output: {every: 0.06, progress: false, mass: {every: 0.01, point: [0, 0, 0], normal: "
                               "[0, 0, 1]}}\n"));
  const fs::path dir = fs::temp_directory_path() / "grains_test_finite_plane";
  const auto sum = run_into(s, dir);
  // mass.csv: header and one row per 0.01 s (first and last included).
  std::ifstream in(dir / "mass.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "step,time_s,grains,mass_kg,lost_particles");
  std::vector<std::array<double, 5>> rows;
  while (std::getline(in, line)) {
    std::array<double, 5> v{};
    std::stringstream ss(line);
    for (auto& x : v) {
      std::string f;
      std::getline(ss, f, ',');
      x = std::stod(f);
    }
    rows.push_back(v);
  }
  ASSERT_GE(rows.size(), 13u);
  const double m1 = 2500 * 4.0 / 3.0 * M_PI * std::pow(0.0005, 3);
  EXPECT_EQ(rows.front()[2], 200);
  EXPECT_NEAR(rows.front()[3], 200 * m1, 1e-9 * 200 * m1);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    EXPECT_GT(rows[k][1], rows[k - 1][1]);
    EXPECT_LE(rows[k][2], rows[k - 1][2]);
    EXPECT_NEAR(rows[k][3], rows[k][2] * m1, 1e-9 * rows[k][3]);  // 10 digits written
  }
  EXPECT_LT(rows.back()[2], 150) << "the silo does not drain";
  EXPECT_EQ(rows.back()[4], static_cast<double>(sum.lost_particles));
  EXPECT_GT(sum.lost_particles, 0);
  // Lost grains plus those still in the domain make up the initial count.
  const auto now = io::count_mass(s.scene);
  EXPECT_EQ(static_cast<std::int64_t>(now.grains) + sum.lost_particles, 200);

  const auto walls = postprocess::read_walls(dir / "frames/walls_000000.vtp");
  // Rebuilt from the records of the frame: the finite plane and the cylinder as the run had them.
  ASSERT_EQ(walls.of<sim::CylinderWall>().size(), 1u);
  ASSERT_EQ(walls.of<sim::PlaneWall>().size(), 1u);
  const auto& a = walls.of<sim::PlaneWall>()[0];
  const auto& run = s.scene.walls.of<sim::PlaneWall>()[0];
  EXPECT_TRUE(a.finite());
  EXPECT_EQ(a.hole_radius, 0.0025);
  EXPECT_EQ(a.normal, run.normal);
  EXPECT_EQ(a.radius, run.radius);
  EXPECT_NEAR(a.point.norm(), 0, 1e-9);
  EXPECT_EQ(walls.of<sim::CylinderWall>()[0].surface.radius, s.scene.walls.of<sim::CylinderWall>()[0].surface.radius);
  // Particle-wall contacts as the analysis counts them: one resting beside
  // the hole touches, one over the middle of the hole does not.
  postprocess::Frame f;
  f.x = {Vec3(0.004, 0, 0.0004), Vec3(0, 0, 0.0004)};
  f.radius = {0.0005, 0.0005};
  const auto z = postprocess::wall_contacts(f, walls);
  EXPECT_EQ(z[0], 1);
  EXPECT_EQ(z[1], 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace grains::test
