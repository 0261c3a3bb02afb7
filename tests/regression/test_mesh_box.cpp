// Mesh walls against plane walls on a whole pour: cases/pour_spheres (10,000
// spheres poured into a 20 d x 20 d box of five planes) run as it is and with
// its box as one mesh wall of 10 triangles (tests/support/mesh_files.hpp
// open_box: the floor and four sides, two triangles each). The two runs start
// from the same particles; the contacts' rounding differs (one mesh wall
// sums a particle's wall contacts in depth order, the planes in wall order),
// so the beds are two realisations of the same pour: their bulk packing
// fractions must agree within the band of packing_references.yaml
// (mesh_box_phi), and both settle.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <unistd.h>

#include "tests/regression/packing_support.hpp"
#include "tests/support/mesh_files.hpp"

namespace grains::test {
namespace {

using namespace packing;

struct Bed {
  double phi = 0, speed = 0;
  std::size_t n = 0;
  double seconds = 0;
};

Bed pour(const std::vector<std::string>& sets) {
  const std::string path = std::string(GRAINS_SOURCE_DIR) + "/cases/pour_spheres/case.yaml";
  auto s = io::make_simulation(io::load_case(path, sets));
  auto& sc = s.scene;
  const auto t0 = std::chrono::steady_clock::now();
  s.pipeline.initialize(sc);
  run_steps(s, sc.clock.n_steps);
  Bed b;
  b.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& p = sc.particles;
  b.n = p.n_owned();
  std::vector<postprocess::Vec3> x(p.x.begin(), p.x.begin() + p.n_owned());
  std::vector<double> rad(p.radius.begin(), p.radius.begin() + p.n_owned());
  const postprocess::Box container{postprocess::Vec3(0, 0, 0), postprocess::Vec3(0.02, 0.02, 1)};
  const auto bulk = postprocess::bulk_region(x, rad, container, 0.002);  // 2 d
  b.phi = postprocess::packing_fraction(x, rad, bulk);
  b.speed = mean_speed(sc);
  return b;
}

TEST(MeshBox, PourIntoATriangulatedBoxPacksAsIntoFivePlanes) {
  const auto ref = reference("mesh_box_phi");
  const std::filesystem::path off =
      std::filesystem::temp_directory_path() / ("grains_mesh_box_" + std::to_string(::getpid()) + ".off");
  write_off(off, open_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.02, 0.02, 0.07)).weld());
  const Bed planes = pour({});
  const Bed mesh = pour({"walls=[{type: mesh, name: box, file: " + off.string() + ", material: grain}]"});
  std::filesystem::remove(off);
  std::cout << "plane box: bulk phi " << planes.phi << ", mean speed " << planes.speed << " m/s, " << planes.seconds
            << " s; mesh box: bulk phi " << mesh.phi << ", mean speed " << mesh.speed << " m/s, " << mesh.seconds
            << " s\n";
  EXPECT_EQ(planes.n, 10000u);
  EXPECT_EQ(mesh.n, 10000u);  // none lost through an edge or a corner
  EXPECT_LT(planes.speed, 0.01);
  EXPECT_LT(mesh.speed, 0.01);
  expect_in_band(ref, mesh.phi - planes.phi, "mesh box phi - plane box phi");
  record("mesh_box", Record().num("phi_planes", planes.phi).num("phi_mesh", mesh.phi).num("seconds_planes", planes.seconds)
                         .num("seconds_mesh", mesh.seconds));
}

}  // namespace
}  // namespace grains::test
