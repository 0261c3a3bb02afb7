// Discharge through mesh walls (cases/hopper_discharge: 2,500 spheres of
// d = 1 mm in a bin of 20 d diameter over an orifice of D = 6 d, closed by a
// mesh gate that slides away at 0.3 s). With a flat bottom (the hopper's cone
// at 90 degrees: a flat triangulated annulus) the mass flow rate follows the
// Beverloo law: the discharge coefficient C = W / (rho_b sqrt(g) (D - 1.5 d)^(5/2)),
// rho_b the fill's bulk density measured before the gate opens, must lie in
// the band of packing_references.yaml beverloo_C (the same band as the plane
// silo's). A conical hopper of half-angle 30 degrees discharges faster than
// the flat bottom (mesh_hopper_30_over_flat). The rate is the slope of the
// mass above the orifice over 0.36-0.56 s, while the bed is still deep.
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
};

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
  std::cout << "flat-bottomed mesh hopper: C = " << C << " (k = 1.5); cone / flat = " << cone.W / flat.W << "\n";
  EXPECT_GT(flat.phi_b, 0.55);
  EXPECT_LT(flat.phi_b, 0.65);
  expect_in_band(refC, C, "flat-bottomed mesh hopper, D = 6 d");
  expect_in_band(refRatio, cone.W / flat.W, "W(30 deg) / W(flat)");
  record("mesh_hopper", Record().num("W_flat", flat.W).num("W_30", cone.W).num("phi_b", flat.phi_b).num("C", C));
}

}  // namespace
}  // namespace grains::test
