// OpenVDB is a module loaded the first time a mesh is decomposed
// (contact/clump/vdb/vdb_module.hpp): a run of spheres never maps it (about
// 27 MB resident per process), and a distance grid still comes out right
// once it is loaded. One test per process (ctest runs each on its own), so
// nothing before it has loaded the module.

#include "clump_test_data.hpp"
#include "contact/clump/distance_grid.hpp"
#include "io/case/case.hpp"
#include "io/run/simulation.hpp"
#include "tests/support/mapped.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

namespace {

using grains::test::mapped;

const char* kSpheres = R"(
title: lazy_openvdb
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
gravity: [0, 0, -9.81]
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}
particles:
  - name: s
    material: m
    radius: 0.0005
    count: 20
    placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}, seed: 1}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: m}
time: {dt: 1.0e-5, end: 1.0e-3}
)";

}  // namespace

TEST(LazyOpenVdb, ASphereRunNeverMapsItAndADistanceGridLoadsIt) {
  ASSERT_FALSE(mapped("libopenvdb")) << "OpenVDB is mapped before anything asked for it";
  auto s = grains::io::make_simulation(grains::io::parse_case(kSpheres, "lazy.yaml"));
  s.pipeline.initialize(s.scene);
  for (int k = 0; k < 100; ++k) s.pipeline.step(s.scene);
  EXPECT_EQ(s.scene.particles.n_owned(), 20u);
  EXPECT_FALSE(mapped("libopenvdb")) << "a run of spheres mapped OpenVDB";
  EXPECT_FALSE(mapped("libgrains_vdb"));

  const auto m = test_mesh("cube.off");  // [-1, 1]^3
  const auto g = grains::clump::compute_distance_grid(m, 16);
  EXPECT_TRUE(mapped("libgrains_vdb"));
  EXPECT_TRUE(mapped("libopenvdb"));
  // The node nearest the centre is about one edge-half deep; every node's
  // value is the exact distance to within the grid's error bound.
  ASSERT_EQ(g.phi.size(), 16u * 16u * 16u);
  EXPECT_NEAR(g.phi[g.index(8, 8, 8)], -(1.0 - 0.5 * g.h), 1e-9);
  EXPECT_LT(g.phi[g.index(0, 0, 0)], 0.0);  // the enclosing cube is the cube itself: corner nodes inside
}

// A module that cannot be loaded is an error that says what is missing and
// where it was looked for (in a child process: the first load is cached).
TEST(LazyOpenVdb, AModuleThatCannotBeLoadedIsAClearError) {
  EXPECT_EXIT(
      {
        setenv("GRAINS_VDB_MODULE", "/nonexistent/libgrains_vdb.so", 1);
        try {
          grains::clump::compute_distance_grid(test_mesh("cube.off"), 8);
        } catch (const std::exception& e) {
          std::cerr << e.what();
          std::exit(3);
        }
        std::exit(0);
      },
      testing::ExitedWithCode(3),
      "needs grains's OpenVDB module \\(libgrains_vdb.so.*GRAINS_VDB_MODULE.*/nonexistent/libgrains_vdb.so");
}
