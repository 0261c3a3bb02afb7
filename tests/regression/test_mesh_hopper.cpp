// Discharge through mesh walls (cases/hopper_discharge: 2,500 spheres of
// d = 1 mm in a bin of 20 d diameter over an orifice of D = 6 d, closed by a
// mesh gate that slides away at 0.3 s). With a flat bottom (the hopper's cone
// at 90 degrees: a flat triangulated annulus) the mass flow rate follows the
// Beverloo law: the discharge coefficient C = W / (rho_b sqrt(g) (D - 1.5 d)^(5/2)),
// rho_b the fill's bulk density measured before the gate opens, must lie in
// the band of packing_references.yaml beverloo_C (the same band as the plane
// silo's). A conical hopper of half-angle 30 degrees discharges faster than
// the flat bottom by the hopper-angle factor of Rose & Tanaka (1956, as given
// by Nedderman 1992, ch. 10): W(theta) / W(flat) = (tan theta tan beta)^-0.35
// for theta < 90 - beta, theta the hopper's half-angle from the vertical and
// beta the angle of the flat bin's dead-zone boundary to the horizontal,
// measured here in the flat run (mesh_hopper_30_over_flat). The rate is the
// slope of the mass above the orifice over 0.36-0.56 s, while the bed is
// still deep.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include "tests/regression/packing_support.hpp"
#include "tests/support/mesh_files.hpp"

namespace grains::test {
namespace {

using namespace packing;

struct Outflow {
  double W = 0, phi_b = 0;
  // Flat bottom: the dead zone's boundary against the horizontal, degrees,
  // with the grains that moved less than 0.5 d (creep) or 2 d as stagnant.
  double beta_creep = 0, beta_flow = 0;
  std::size_t points_creep = 0, points_flow = 0;  // rings with flowing grains
};

using Vec3 = sim::Vec3;

// Grain positions indexed by id (NaN: the grain has left the domain).
std::vector<Vec3> by_id(const sim::ParticleStore& p) {
  std::vector<Vec3> x;
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    const auto k = static_cast<std::size_t>(p.id[i]);
    if (k >= x.size()) x.resize(k + 1, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
    x[k] = p.x[i];
  }
  return x;
}

// The stagnant zone of a flat-bottomed bin in discharge: a grain that moved
// less than `moved` diameters between two instants is stagnant. In each ring of
// width d between the orifice's rim and the bin's wall, the boundary lies at
// the height of the lowest grain that moved (the flowing core above the
// dead corner); beta is the angle of the straight line through those
// heights against the horizontal (Nedderman 1992, ch. 10: the boundary of
// the dead zone, whose angle the hopper-angle factor compares the cone with).
double stagnant_boundary_angle(const std::vector<Vec3>& x0, const std::vector<Vec3>& x1, double d, double rim,
                               double wall, double moved, std::size_t& points) {
  std::vector<double> r, z;
  for (double a = rim; a + d <= wall - d + 1e-12; a += d) {
    double lowest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < x0.size(); ++i) {
      const double ri = std::hypot(x0[i].x(), x0[i].y());
      if (!(ri >= a && ri < a + d && x0[i].z() > 0)) continue;
      const bool flowed = i >= x1.size() || !x1[i].allFinite() || (x1[i] - x0[i]).norm() > moved * d;
      if (flowed) lowest = std::min(lowest, x0[i].z());
    }
    if (std::isfinite(lowest)) r.push_back(a + 0.5 * d), z.push_back(lowest);
  }
  points = r.size();
  if (r.size() < 3) return 0;
  return std::atan(fit_line(r, z).b) * 180 / M_PI;
}

Outflow discharge(double theta) {
  const std::filesystem::path off = std::filesystem::temp_directory_path() /
                                    ("grains_hopper_" + std::to_string(::getpid()) + "_" + std::to_string(int(theta)) + ".off");
  write_off(off, hopper(theta, 0.003, 0.01, 0.03, 64).weld());
  const double hc = theta >= 90 ? 0 : 0.007 / std::tan(theta * M_PI / 180);
  std::ostringstream region;
  region.precision(12);
  region << "particles.0.placement.region={min: [-0.0065, -0.0065, " << hc + 0.0006 << "], max: [0.0065, 0.0065, "
         << hc + 0.0295 << "]}";
  const std::string path = std::string(GRAINS_SOURCE_DIR) + "/cases/hopper_discharge/case.yaml";
  auto s = io::make_simulation(io::load_case(path, {"walls.0.file=" + off.string(), region.str(), "time.end=0.56"}));
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  const double dt = sc.clock.dt;
  Outflow r;
  std::vector<double> t, m;
  std::vector<Vec3> x_a;  // the flat bin's grains (by id order) when the rate is first sampled
  while (sc.clock.step < sc.clock.n_steps) {
    s.pipeline.step(sc);
    const auto& p = sc.particles;
    if (theta >= 90 && r.phi_b == 0 && sc.clock.time >= 0.29) {  // the settled fill: a box in the bin, 2 d from the wall
      std::vector<postprocess::Vec3> x(p.x.begin(), p.x.begin() + static_cast<std::ptrdiff_t>(p.n_owned()));
      std::vector<double> rad(p.radius.begin(), p.radius.begin() + static_cast<std::ptrdiff_t>(p.n_owned()));
      double top = 0;
      for (const auto& xi : x) top = std::max(top, xi.z());
      const postprocess::Box box{postprocess::Vec3(-0.0055, -0.0055, hc + 0.002), postprocess::Vec3(0.0055, 0.0055, top - 0.003)};
      r.phi_b = postprocess::packing_fraction(x, rad, box);
    }
    if (theta >= 90 && sc.clock.time >= 0.36 && x_a.empty()) x_a = by_id(p);
    if (sc.clock.time >= 0.36 && sc.clock.step % std::max<std::int64_t>(1, std::llround(0.005 / dt)) == 0) {
      double mass = 0;
      for (std::size_t i = 0; i < p.n_owned(); ++i)
        if (p.x[i].z() > 0) mass += p.mass[i];
      t.push_back(sc.clock.time);
      m.push_back(mass);
    }
  }
  std::filesystem::remove(off);
  r.W = -fit_line(t, m).b;
  if (theta >= 90) {
    const auto x_b = by_id(sc.particles);
    r.beta_creep = stagnant_boundary_angle(x_a, x_b, 0.001, 0.003, 0.01, 0.5, r.points_creep);
    r.beta_flow = stagnant_boundary_angle(x_a, x_b, 0.001, 0.003, 0.01, 2.0, r.points_flow);
  }
  std::cout << "hopper half-angle " << theta << " deg: W = " << r.W * 1e3 << " g/s over " << t.size()
            << " samples" << (theta >= 90 ? ", fill phi_b = " + std::to_string(r.phi_b) : std::string()) << "\n";
  return r;
}

TEST(MeshHopper, FlatBottomFollowsBeverlooAndTheConeDischargesFaster) {
  const auto refC = reference("beverloo_C");
  const auto refRatio = reference("mesh_hopper_30_over_flat");
  const Outflow flat = discharge(90), cone = discharge(30);
  const double d = 0.001, D = 0.006, rho = 2500;
  const double C = flat.W / (flat.phi_b * rho * std::sqrt(9.81) * std::pow(D - 1.5 * d, 2.5));
  // Rose & Tanaka's hopper-angle factor with the flat bin's own dead zone:
  // its boundary creeps (it is not sharp over the 0.2 s measured), so beta
  // is bracketed by the boundaries of the grains that moved 0.5 d and 2 d.
  const auto F = [](double theta_deg, double beta_deg) {
    const double rad = M_PI / 180;
    return theta_deg < 90 - beta_deg ? std::pow(std::tan(theta_deg * rad) * std::tan(beta_deg * rad), -0.35) : 1.0;
  };
  const double F_hi = F(30, flat.beta_creep), F_lo = F(30, flat.beta_flow), ratio = cone.W / flat.W;
  std::cout << "flat-bottomed mesh hopper: C = " << C << " (k = 1.5); dead zone boundary at beta = " << flat.beta_creep
            << " (0.5 d) .. " << flat.beta_flow << " deg (2 d); cone / flat = " << ratio
            << ", Rose & Tanaka F(30 deg, beta) = " << F_lo << " .. " << F_hi << "\n";
  EXPECT_GT(flat.phi_b, 0.55);
  EXPECT_LT(flat.phi_b, 0.65);
  expect_in_band(refC, C, "flat-bottomed mesh hopper, D = 6 d");
  expect_in_band(refRatio, ratio, "W(30 deg) / W(flat)");
  EXPECT_GE(flat.points_creep, 4u);  // rings between the rim and the wall with flowing grains (of 6)
  EXPECT_GE(flat.points_flow, 4u);
  EXPECT_LT(flat.beta_creep, flat.beta_flow);
  // The upper bound is the one with teeth: F_lo (about 1.05) lies below the
  // band's 1.1, and is 1 once beta_flow reaches 60 degrees.
  EXPECT_GE(ratio, F_lo) << "the cone discharges slower than Rose & Tanaka's factor with the flat bin's dead zone";
  EXPECT_LE(ratio, F_hi) << "the cone discharges faster than Rose & Tanaka's factor with the flat bin's dead zone";
  record("mesh_hopper", Record().num("W_flat", flat.W).num("W_30", cone.W).num("phi_b", flat.phi_b).num("C", C)
                            .num("beta_creep", flat.beta_creep).num("beta_flow", flat.beta_flow).num("F_lo", F_lo)
                            .num("F_hi", F_hi));
}

}  // namespace
}  // namespace grains::test
