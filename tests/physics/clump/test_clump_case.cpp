// Clump shapes in case files: errors with file:line:column, and the cache of
// mesh decompositions.
#include <gtest/gtest.h>

#include "io/case/clump_shapes.hpp"
#include "tests/physics/clump/clump_cases.hpp"

namespace grains::test {
namespace {

std::string case_with_shape(const std::string& shape) {
  return "domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}\nmaterials:\n" +
         material("grain", 2500, 1e7, 0.3, 0.5, 0.0) +
         "particles:\n  - name: a\n    material: grain\n    radius: 0.001\n    count: 1\n    shape: " + shape +
         "\n    placement: {type: lattice, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}\n"
         "time: {dt_rayleigh: 0.2, end: 0.001}\n";
}

std::string first_error(const std::string& shape) {
  try {
    (void)io::parse_case(case_with_shape(shape), "c.yaml");
  } catch (const io::CaseError& e) {
    return e.messages.empty() ? "" : e.messages.front();
  }
  return "";
}

TEST(ClumpCase, ErrorsSayWhereAndWhat) {
  (void)clump_test_dir();
  std::string e = first_error("{type: clump}");
  EXPECT_NE(e.find("c.yaml:9:12"), std::string::npos) << e;
  EXPECT_NE(e.find("needs file"), std::string::npos) << e;
  e = first_error("{type: clump, file: /nonexistent/c.yaml}");
  EXPECT_NE(e.find("c.yaml:9:"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot open clump file"), std::string::npos) << e;
  e = first_error("{type: clump, file: a.yaml, mesh: b.off}");
  EXPECT_NE(e.find("not both"), std::string::npos) << e;
  e = first_error("{type: clump, mesh: " + std::string(GRAINS_SOURCE_DIR) + "/tests/data/meshes/open_box.off}");
  EXPECT_NE(e.find("c.yaml:9:"), std::string::npos) << e;
  EXPECT_NE(e.find("boundary"), std::string::npos) << e;  // the mesh validation's message, passed on
  e = first_error("{type: ellipsoid, aspect_ratio: 2, grid: 8}");
  EXPECT_NE(e.find("type: clump only"), std::string::npos) << e;
  e = first_error("{type: clump, mesh: " + cube_mesh() + ", grid: 2}");
  EXPECT_NE(e.find("grid"), std::string::npos) << e;
}

// A mesh decomposition is cached under a name from the mesh bytes and the
// parameters; the cached file gives the same shape.
TEST(ClumpCase, MeshDecompositionIsCachedByContentAndParameters) {
  (void)clump_test_dir();
  const auto f6 = io::clump_cache_file(cube_mesh(), 6, 0.25), f7 = io::clump_cache_file(cube_mesh(), 7, 0.25),
             f6mu = io::clump_cache_file(cube_mesh(), 6, 0.5);
  EXPECT_NE(f6, f7);
  EXPECT_NE(f6, f6mu);
  EXPECT_EQ(f6.parent_path(), clump_test_dir() / "cache");
  const auto a = io::clump_shape_from_mesh(cube_mesh(), 6, 0.25);
  ASSERT_TRUE(fs::exists(f6));
  const auto b = io::normalised_clump_shape(clump::load_clump_yaml(f6.string()), "cached");
  ASSERT_EQ(a->radii.size(), b.radii.size());
  EXPECT_EQ(a->radii.size(), 40u);
  for (std::size_t k = 0; k < b.radii.size(); ++k) EXPECT_NEAR(a->radii[k], b.radii[k], 1e-12);
  EXPECT_NEAR(a->volume, b.volume, 1e-12);
  double bound = 0;
  for (std::size_t k = 0; k < b.radii.size(); ++k) bound = std::max(bound, b.centres[k].norm() + b.radii[k]);
  EXPECT_NEAR(bound, 1.0, 1e-12);  // normalised to a bounding radius of 1
}

}  // namespace
}  // namespace grains::test
