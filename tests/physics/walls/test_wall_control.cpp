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
std::string box_case(int count, const std::string& walls, double end, const std::string& extra = "",
                     double mu = 0.3) {
  std::ostringstream y;
  y << "domain: {min: [-0.001, -0.001, -0.001], max: [0.011, 0.011, 0.021]}\n"
       "gravity: [0, 0, 0]\n"
       "materials:\n"
    << material("grain", 2500, 1e7, 0.3, 0.5, mu) << material("wall", 2500, 1e7, 0.3, 0.5, 0.0)
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

// ---- Stress measurement (output.stress) ----
namespace grains::test {
namespace {

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  int col(const std::string& name) const {
    for (std::size_t k = 0; k < header.size(); ++k)
      if (header[k] == name) return static_cast<int>(k);
    throw std::runtime_error("no column " + name);
  }
};
Csv read_csv(const std::filesystem::path& f) {
  Csv c;
  std::ifstream in(f);
  std::string line, cell;
  std::getline(in, line);
  std::stringstream h(line);
  while (std::getline(h, cell, ',')) c.header.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<double> v;
    while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
    c.rows.push_back(v);
  }
  return c;
}

TEST(StressOutput, TheLoveWeberStressOfAFrictionlessBoxIsWhatItsServoWallsHold) {
  // Without friction (grains and walls) and without gravity, the stress of
  // the whole box in equilibrium is the boundary's: each wall's stress on the
  // normal component, whatever the packing.
  const std::string c = "{stress: 5000, max_speed: 0.1}";
  const std::string y = box_case(300, side_walls(c) + plane("floor", "[0, 0, 0]", "[0, 0, 1]", c) +
                                    plane("lid", "[0, 0, 0.0205]", "[0, 0, -1]", c),
                           0.3, "output: {progress: false, vtk: false, stress: {every_steps: 100}}\n", 0.0);
  auto s = from_yaml(y);
  TempDir tmp("stress_box");
  run_into(s, tmp.path);
  const Csv st = read_csv(tmp.path / "stress.csv");
  ASSERT_FALSE(st.rows.empty());
  const auto& last = st.rows.back();
  ASSERT_EQ(static_cast<std::int64_t>(last[0]), s.scene.clock.step) << "the last step is measured";
  for (const char* k : {"sxx_Pa", "syy_Pa", "szz_Pa", "pressure_Pa"})
    EXPECT_NEAR(last[static_cast<std::size_t>(st.col(k))] / 5000, 1.0, 1e-3) << k;
  for (const char* k : {"sxy_Pa", "sxz_Pa", "syz_Pa"})
    EXPECT_LT(std::abs(last[static_cast<std::size_t>(st.col(k))]) / 5000, 0.05) << k;
  // The box's volume and solid fraction, from the walls and the grains.
  const double lx = wall(s, "x1").point.x() - wall(s, "x0").point.x();
  const double ly = wall(s, "y1").point.y() - wall(s, "y0").point.y();
  const double lz = wall(s, "lid").point.z() - wall(s, "floor").point.z();
  double vs = 0;
  for (std::size_t i = 0; i < s.scene.particles.n_owned(); ++i) vs += 4.0 / 3.0 * M_PI * std::pow(s.scene.particles.radius[i], 3);
  EXPECT_NEAR(last[static_cast<std::size_t>(st.col("volume_m3"))] / (lx * ly * lz), 1.0, 1e-9);
  EXPECT_NEAR(last[static_cast<std::size_t>(st.col("solid_fraction"))] / (vs / (lx * ly * lz)), 1.0, 1e-9);
  EXPECT_EQ(last[static_cast<std::size_t>(st.col("grains"))], 300);
}

TEST(StressOutput, TheVerticalStressOfAStaticBedIsTheWeightAboveInEveryBin) {
  // A bed settled on a floor, periodic in x and y (no wall to hold it up by
  // friction): through any plane z the grains above push with their weight,
  // so sigma_zz averaged over a bin [z0, z1] is (g / (A w)) sum_i m_i
  // |[z0, z1] below z_i| -- with bins of one grain diameter.
  std::ostringstream y;
  y << "domain: {min: [0, 0, 0], max: [0.005, 0.005, 0.02], periodic: [true, true, false]}\n"
       "gravity: [0, 0, -9.81]\n"
       "materials:\n"
    << material("grain", 2500, 1e7, 0.3, 0.3, 0.3)
    << "particles:\n"
       "  - {name: bed, material: grain, radius: {distribution: uniform, min: 0.0004, max: 0.0005}, count: 300, "
       "placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.005, 0.005, 0.02]}, seed: 3}}\n"
       "walls:\n  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain}\n"
       "time: {dt: 5.0e-6, end: 0.4}\n"
       "output: {progress: false, vtk: false, stress: {every_steps: 4000, profile_axis: z, bins: 10, "
       "region: {min: [0, 0, 0], max: [0.005, 0.005, 0.01]}}}\n";
  auto s = from_yaml(y.str());
  TempDir tmp("stress_column");
  run_into(s, tmp.path);
  const Csv pr = read_csv(tmp.path / "profile.csv");
  const auto& p = s.scene.particles;
  const double A = 0.005 * 0.005, w = 0.001, g = 9.81;
  int checked = 0;
  for (const auto& row : pr.rows) {
    if (static_cast<std::int64_t>(row[0]) != s.scene.clock.step) continue;
    const int b = static_cast<int>(row[2]);
    const double z0 = b * w, z1 = z0 + w;
    double expect = 0;
    for (std::size_t i = 0; i < p.n_owned(); ++i) expect += p.mass[i] * std::clamp(p.x[i].z() - z0, 0.0, w);
    expect *= g / (A * w);
    // The solid fraction: the spheres' volume between z0 and z1 (spherical
    // caps and slabs), over the bin's volume (z is not periodic: each sphere once).
    double solid = 0;
    for (std::size_t i = 0; i < p.n_owned(); ++i) {
      const double r = p.radius[i], a = std::max(z0, p.x[i].z() - r) - p.x[i].z(),
                   c = std::min(z1, p.x[i].z() + r) - p.x[i].z();
      if (c > a) solid += M_PI * (r * r * (c - a) - (c * c * c - a * a * a) / 3);
    }
    EXPECT_NEAR(row[static_cast<std::size_t>(pr.col("solid_fraction"))], solid / (A * w), 1e-9) << "bin " << b;
    const double szz = row[static_cast<std::size_t>(pr.col("szz_Pa"))];
    if (expect > 1)
      EXPECT_NEAR(szz / expect, 1.0, 0.01) << "bin " << b << " of " << (z0 + z1) / 2 << " m";
    else
      EXPECT_LT(std::abs(szz), 0.5) << "bin " << b;
    ++checked;
  }
  EXPECT_EQ(checked, 10);
}

TEST(StressOutput, TheKineticStressOfAGasIsSumMvvAboutTheBinsMeanVelocity) {
  // Grains far apart (no contact), no gravity: two interleaved lattices
  // moving at (+u, 0, w) and (-u, 0, w); the stress is all kinetic. (The
  // CSV holds 10 significant digits.)
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [0, 0, 0], max: [0.02, 0.02, 0.02]}\n"
       "gravity: [0, 0, 0]\n"
       "materials:\n"
    << material("grain", 2500, 1e7, 0.3, 0.5, 0.3)
    << "particles:\n"
       "  - {name: a, material: grain, radius: 0.0005, velocity: [0.3, 0, 0.1], "
       "placement: {type: lattice, spacing: 0.004, region: {min: [0.001, 0.001, 0.001], max: [0.02, 0.02, 0.0195]}}}\n"
       "  - {name: b, material: grain, radius: 0.0005, velocity: [-0.2, 0, 0.1], "
       "placement: {type: lattice, spacing: 0.004, region: {min: [0.003, 0.003, 0.003], max: [0.02, 0.02, 0.0195]}}}\n"
       "time: {dt: 1.0e-5, end: 0.001}\n"
       "output: {progress: false, vtk: false, stress: {every_steps: 100, profile_axis: z, bins: 4}}\n";
  auto s = from_yaml(y.str());
  TempDir tmp("stress_gas");
  run_into(s, tmp.path);
  const auto& p = s.scene.particles;
  const Csv pr = read_csv(tmp.path / "profile.csv"), st = read_csv(tmp.path / "stress.csv");
  const double V = 0.02 * 0.02 * 0.02, Vb = V / 4;
  std::vector<double> m(4, 0), mu(4, 0), kxx(4, 0);
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    const int b = static_cast<int>(p.x[i].z() / 0.005);
    m[b] += p.mass[i], mu[b] += p.mass[i] * p.v[i].x();
  }
  double total_xx = 0;
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    const int b = static_cast<int>(p.x[i].z() / 0.005);
    const double wx = p.v[i].x() - mu[b] / m[b];
    kxx[b] += p.mass[i] * wx * wx;
    total_xx += p.mass[i] * wx * wx;
  }
  int rows = 0;
  for (const auto& row : pr.rows) {
    if (static_cast<std::int64_t>(row[0]) != s.scene.clock.step) continue;
    const auto b = static_cast<std::size_t>(row[2]);
    ASSERT_GT(m[b], 0);
    EXPECT_NEAR(row[static_cast<std::size_t>(pr.col("sxx_Pa"))], kxx[b] / Vb, 1e-9 * kxx[b] / Vb) << b;
    EXPECT_NEAR(row[static_cast<std::size_t>(pr.col("kxx_Pa"))], kxx[b] / Vb, 1e-9 * kxx[b] / Vb) << b;
    EXPECT_NEAR(row[static_cast<std::size_t>(pr.col("vx_mps"))], mu[b] / m[b], 1e-10) << b;
    EXPECT_NEAR(row[static_cast<std::size_t>(pr.col("kzz_Pa"))], 0.0, 1e-12) << "all move at the same w";
    EXPECT_NEAR(row[static_cast<std::size_t>(pr.col("kxz_Pa"))], 0.0, 1e-12) << b;
    ++rows;
  }
  EXPECT_EQ(rows, 4);
  EXPECT_NEAR(st.rows.back()[static_cast<std::size_t>(st.col("kxx_Pa"))], total_xx / V, 1e-9 * total_xx / V)
      << "the region's kinetic part is the sum of its bins'";
}

TEST(StressOutput, ErrorsAreLocated) {
  const std::string base = box_case(10, side_walls() + plane("floor", "[0, 0, 0]", "[0, 0, 1]"), 0.01);
  std::string e = errors_of(base + "output: {stress: {every_steps: 10, bins: 4}}\n");
  EXPECT_NE(e.find("output.stress"), std::string::npos) << e;
  EXPECT_NE(e.find("needs both profile_axis and bins"), std::string::npos) << e;
  e = errors_of(base + "output: {stress: {region: {min: [0, 0, 0.01], max: [0.01, 0.01, 0]}}}\n");
  EXPECT_NE(e.find("max must exceed min"), std::string::npos) << e;
  e = errors_of(base + "output: {stress: {profile_axis: w, bins: 3}}\n");
  EXPECT_NE(e.find("profile_axis"), std::string::npos) << e;
  std::string ark = base + "output: {stress: {every_steps: 10}}\n";
  ark.replace(ark.find("time: {"), 7, "time: {integrator: arkode, ");
  e = errors_of(ark);
  EXPECT_NE(e.find("output.stress measures with the Verlet integrator"), std::string::npos) << e;
  EXPECT_NE(e.find("case.yaml:"), std::string::npos) << e;
}

}  // namespace
}  // namespace grains::test

// ---- Lees–Edwards boundaries (domain.shear) ----
namespace grains::test {
namespace {

std::string shear_cell(double rate, const std::string& extra, double end, int count = 320,
                       const std::string& particles = "") {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.006], periodic: true, shear: {rate: " << rate
    << ", flow: x, gradient: y" << extra << "}}\n"
       "gravity: [0, 0, 0]\n"
       "materials:\n"
    << material("grain", 2500, 1e7, 0.3, 0.7, 0.5) << "particles:\n";
  if (particles.empty())
    y << "  - {name: bed, material: grain, radius: {distribution: uniform, min: 0.00045, max: 0.00055}, count: "
      << count << ", placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.006]}, seed: 5}}\n";
  else
    y << particles;
  y << "time: {dt_rayleigh: 0.2, end: " << end << "}\n";
  return y.str();
}

TEST(LeesEdwards, AGrainLeavingThroughTheShearedFaceComesBackDisplacedAndSlowed) {
  sim::Domain d;
  d.lo = sim::Vec3(0, 0, 0), d.hi = sim::Vec3(0.01, 0.02, 0.006);
  d.periodic = {true, true, true};
  d.shear.flow = 0, d.shear.gradient = 1, d.shear.rate = 30;
  const double U = 30 * 0.02, t = 0.0123;
  EXPECT_DOUBLE_EQ(d.shear_speed(), U);
  EXPECT_NEAR(d.shear_offset(t), std::fmod(U * t, 0.01), 1e-15);
  sim::Vec3 x(0.004, 0.0201, 0.003), v(0.3, 0.1, 0);
  d.wrap(x, v, t);  // out through the top: in through the bottom, behind by the offset, slower by U
  EXPECT_NEAR(x.y(), 0.0001, 1e-15);
  EXPECT_NEAR(x.x(), std::fmod(0.004 - std::fmod(U * t, 0.01) + 0.01, 0.01), 1e-15);
  EXPECT_DOUBLE_EQ(v.x(), 0.3 - U);
  sim::Vec3 x2(0.004, -0.0001, 0.003), v2(0.3, -0.1, 0);
  d.wrap(x2, v2, t);  // and the other way
  EXPECT_NEAR(x2.y(), 0.0199, 1e-15);
  EXPECT_NEAR(x2.x(), std::fmod(0.004 + std::fmod(U * t, 0.01), 0.01), 1e-15);
  EXPECT_DOUBLE_EQ(v2.x(), 0.3 + U);
}

TEST(LeesEdwards, GrainsTouchAcrossTheShearedFaceAndConserveMomentum) {
  // Two grains, one just under the top face and one just over the bottom
  // one, closing on each other through it; the image above the cell slides
  // along x at U. They must collide through the face: their y velocities
  // turn round, friction drags them apart along x, and both momenta are
  // conserved (what one gains the other loses).
  const double r = 0.0005, vy = 0.05;
  std::ostringstream ps;
  ps.precision(17);
  ps << single("a", "grain", sim::Vec3(0.005, 0.01 - 1.1 * r, 0.003), r, sim::Vec3(0, vy, 0))
     << single("b", "grain", sim::Vec3(0.005, 1.1 * r, 0.003), r, sim::Vec3(0, -vy, 0));
  auto s = from_yaml(shear_cell(2.0, ", initial_profile: false", 0.004, 0, ps.str()));
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  const auto& p = sc.particles;
  while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
  const auto a = index_of(p, 0), b = index_of(p, 1);
  ASSERT_LT(a, p.n_owned());
  ASSERT_LT(b, p.n_owned());
  // (A grain that crossed the face since the last rebuild is still beyond
  // it, at its own velocity: compare the velocities as they are.)
  EXPECT_LT(p.v[a].y(), 0) << "a bounced back down";
  EXPECT_GT(p.v[b].y(), 0) << "b bounced back up";
  EXPECT_NEAR(p.v[a].y() + p.v[b].y(), 0.0, 1e-12 * vy) << "momentum along y";
  EXPECT_GT(p.v[a].x(), 0) << "dragged along by the image above, moving at +U";
  EXPECT_NEAR(p.v[a].x() + p.v[b].x(), 0.0, 1e-12 * vy) << "momentum along x";
}

TEST(LeesEdwards, AShearedCellFlowsOnTheLinearProfileWithAUniformShearStress) {
  const double rate = 20;
  auto s = from_yaml(shear_cell(rate, "", 1.2) +
                     "output: {progress: false, vtk: false, stress: {every_steps: 200, profile_axis: y, bins: 5, "
                     "average_after: 0.6}}\n");
  TempDir tmp("shear_cell");
  run_into(s, tmp.path);
  const Csv pm = read_csv(tmp.path / "profile_mean.csv");
  ASSERT_EQ(pm.rows.size(), 5u);
  const double U = rate * 0.01;
  double sxy_mean = 0;
  for (const auto& row : pm.rows) sxy_mean += row[static_cast<std::size_t>(pm.col("sxy_Pa"))] / 5;
  EXPECT_LT(sxy_mean, 0) << "the grains resist the shear (compressive > 0: sigma_xy < 0 for du_x/dy > 0)";
  for (const auto& row : pm.rows) {
    const double y = row[static_cast<std::size_t>(pm.col("position_m"))];
    const double u = row[static_cast<std::size_t>(pm.col("vx_mps"))];
    EXPECT_NEAR(u, rate * (y - 0.005), 0.03 * U) << "the mean flow at y = " << y;
    EXPECT_NEAR(row[static_cast<std::size_t>(pm.col("sxy_Pa"))] / sxy_mean, 1.0, 0.25) << "y = " << y;
    EXPECT_NEAR(row[static_cast<std::size_t>(pm.col("vy_mps"))], 0.0, 0.01 * U);
  }
  // The whole cell's shear stress is its bins' mean (every branch counted once).
  const Csv st = read_csv(tmp.path / "stress.csv");
  double cell = 0;
  int rows = 0;
  for (const auto& row : st.rows)
    if (row[1] >= 0.6) cell += row[static_cast<std::size_t>(st.col("sxy_Pa"))], ++rows;
  EXPECT_NEAR(cell / rows / sxy_mean, 1.0, 1e-6);
}

TEST(LeesEdwards, TheOffsetStaysContinuousWhenTheCellHeightChanges) {
  // The pressure servo changes L_g: the images' offset must not jump, and
  // grows at the new speed rate L_g afterwards.
  sim::Domain d;
  d.lo = sim::Vec3(0, 0, 0), d.hi = sim::Vec3(0.01, 0.02, 0.006);
  d.periodic = {true, true, true};
  d.shear.flow = 0, d.shear.gradient = 1, d.shear.rate = 30, d.shear.pressure = 100;
  const double t1 = 0.0123, t2 = 0.02;
  const double before = d.shear_travel(t1);
  EXPECT_DOUBLE_EQ(before, 30 * 0.02 * t1);
  d.set_gradient_length(0.018, t1);
  EXPECT_DOUBLE_EQ(d.hi.y(), 0.018);
  EXPECT_NEAR(d.shear_travel(t1), before, 1e-15);
  EXPECT_NEAR(d.shear_travel(t2), before + 30 * 0.018 * (t2 - t1), 1e-15);
  EXPECT_NEAR(d.shear_offset(t2), std::fmod(before + 30 * 0.018 * (t2 - t1), 0.01), 1e-15);
}

// The mean of a stress.csv column over the rows from time t0 on.
double csv_mean_after(const std::filesystem::path& f, const std::string& column, double t0, int* rows = nullptr) {
  const Csv st = read_csv(f);
  double sum = 0;
  int n = 0;
  for (const auto& row : st.rows)
    if (row[1] >= t0) sum += row[static_cast<std::size_t>(st.col(column))], ++n;
  if (rows) *rows = n;
  return n > 0 ? sum / n : std::nan("");
}

TEST(ShearPressure, TheCellCompressesOrDilatesUntilItHoldsThePressure) {
  // Da Cruz et al.'s pressure-imposed simple shear, both ways, as a
  // two-stage run. Stage 1: a dilute cell (phi 0.28) sheared at 20/s under
  // a normal stress it cannot bear (40 Pa): the servo shrinks its height
  // until the measured sigma_yy (contact + kinetic, the stress output's own
  // measurement, not the servo's sums) holds the target. Stage 2, from
  // stage 1's last checkpoint with the target lowered to 10 Pa: the cell
  // grows again and holds the new target.
  const std::string out = "output: {progress: false, vtk: false, stress: {every_steps: 100, average_after: ";
  auto s1 = from_yaml(shear_cell(20, ", pressure: 40, gain: 0.5", 1.2) + out + "0.8}}\n" +
                      "checkpoint: {every: 0.6}\n");
  TempDir tmp("shear_pressure");
  run_into(s1, tmp.path / "stage1");
  const auto st1 = tmp.path / "stage1" / "stress.csv";
  const double V1 = csv_mean_after(st1, "volume_m3", 0.8);
  EXPECT_LT(V1, 0.75 * 0.01 * 0.01 * 0.006) << "the cell compressed (its height from 10 mm)";
  int n = 0;
  EXPECT_NEAR(csv_mean_after(st1, "syy_Pa", 0.8, &n) / 40, 1.0, 0.03) << "the mean normal stress across the gradient";
  EXPECT_GT(n, 20);
  const double phi1 = csv_mean_after(st1, "solid_fraction", 0.8);
  EXPECT_GT(phi1, 0.45) << "denser than the start";

  auto s2 = from_yaml(shear_cell(20, ", pressure: 10, gain: 0.5", 2.0) + out + "1.6}}\n");
  io::RunOptions opt;
  opt.out_dir = tmp.path / "stage2";
  opt.quiet = true;
  std::filesystem::path last;
  for (const auto& e : std::filesystem::directory_iterator(tmp.path / "stage1" / "checkpoints"))
    if (e.path().extension() == ".h5" && (last.empty() || e.path() > last)) last = e.path();
  opt.restart = last;
  io::run(s2, opt);
  EXPECT_GT(s2.scene.clock.time, 1.99);
  // (Measured: phi 0.565 at 40 Pa, I = 0.16; 0.544 at 10 Pa, I = 0.32.)
  const auto st2 = tmp.path / "stage2" / "stress.csv";
  EXPECT_GT(csv_mean_after(st2, "volume_m3", 1.6), 1.02 * V1) << "under a lower pressure the cell dilates";
  EXPECT_LT(csv_mean_after(st2, "solid_fraction", 1.6), phi1 - 0.01);
  EXPECT_NEAR(csv_mean_after(st2, "syy_Pa", 1.6, &n) / 10, 1.0, 0.05);
  EXPECT_GT(n, 20);
}

TEST(LeesEdwards, ErrorsAreLocated) {
  std::string y = shear_cell(20, "", 0.01);
  std::string e = errors_of(std::string(y).replace(y.find("periodic: true"), 14, "periodic: [true, false, true]"));
  EXPECT_NE(e.find("domain.shear"), std::string::npos) << e;
  EXPECT_NE(e.find("a shear rate needs periodic y (the gradient axis)"), std::string::npos) << e;
  e = errors_of(std::string(y).replace(y.find("gradient: y"), 11, "gradient: x"));
  EXPECT_NE(e.find("flow and gradient must be different axes"), std::string::npos) << e;
  e = errors_of(std::string(y).replace(y.find("rate: 20"), 8, "rate: 0"));
  EXPECT_NE(e.find("rate must not be 0"), std::string::npos) << e;
  std::string ark = y;
  ark.replace(ark.find("time: {"), 7, "time: {integrator: arkode, ");
  e = errors_of(ark);
  EXPECT_NE(e.find("domain.shear (Lees-Edwards) moves its images by the Verlet step"), std::string::npos) << e;
  EXPECT_NE(e.find("case.yaml:"), std::string::npos) << e;
  e = errors_of(std::string(y).replace(y.find("gradient: y"), 11, "gradient: y, pressure: -5"));
  EXPECT_NE(e.find("pressure must be compressive, > 0"), std::string::npos) << e;
  e = errors_of(std::string(y).replace(y.find("gradient: y"), 11, "gradient: y, gain: 0.3"));
  EXPECT_NE(e.find("gain goes with pressure"), std::string::npos) << e;
}

}  // namespace
}  // namespace grains::test
