// Finer grids (label `long`): the Hausdorff bound on the bunny and the cow,
// and the bunny's epsilon and ball counts against the seed's Table 2 at its
// two finest resolutions.

#include "clump_test_data.hpp"
#include "contact/clump/ball_union.hpp"
#include "contact/clump/hausdorff.hpp"
#include "contact/clump/mesh_distance.hpp"
#include "contact/clump/sphere_decomposition.hpp"

#include <gtest/gtest.h>

using namespace grains::clump;

namespace {
SphereDecomposition check(const std::string& name, int n) {
  SCOPED_TRACE(name + " at N = " + std::to_string(n));
  const auto m = test_mesh(name);
  const MeshDistance d(m);
  const DistanceGrid g = compute_distance_grid(m, n, &d);
  const SphereDecomposition s = decompose(g, {n, 0.25, GreedyKey::distance});
  const HausdorffResult h = measure_hausdorff(m, d, BallUnion(s.a3), 0.5 * g.h, &g);
  EXPECT_LE(h.union_to_mesh, s.epsilon * (1 + 1e-9));
  EXPECT_LE(h.hausdorff, std::max(s.epsilon, h.node_cover_radius) * (1 + 1e-9));
  std::printf("%s N=%d n1=%zu n3=%zu eps=%.5f dH=%.5f (%.3f eps) cover=%.5f\n", name.c_str(), n, s.n1(), s.n3(),
              s.epsilon, h.hausdorff, h.hausdorff / s.epsilon, h.node_cover_radius);
  return s;
}

// The seed's Table 2 (bunny, mu = 0.25) against ours (docs/decomposition.md):
// the same epsilon (1 %); n1 = n2 17-41 % above the seed's (its "SDF" node
// order is not reproducible), n3 below or near the seed's (our covering step
// keeps fewer balls at fine grids): bands that hold every resolution measured
// and fail if the decomposition drifts.
void check_table2(const SphereDecomposition& s, double eps, std::size_t n1, std::size_t n3) {
  EXPECT_NEAR(s.epsilon / eps, 1.0, 0.01);
  EXPECT_GE(s.n1(), n1);
  EXPECT_LE(static_cast<double>(s.n1()), 1.45 * static_cast<double>(n1));
  EXPECT_GE(static_cast<double>(s.n3()), 0.6 * static_cast<double>(n3));
  EXPECT_LE(static_cast<double>(s.n3()), 1.1 * static_cast<double>(n3));
}
}  // namespace

TEST(HausdorffBoundLong, Bunny64) { check_table2(check("bunny00.off", 64), 0.0135, 6842, 1024); }
TEST(HausdorffBoundLong, Bunny128) { check_table2(check("bunny00.off", 128), 0.0068, 26217, 3686); }
TEST(HausdorffBoundLong, Cow64) { (void)check("cow.off", 64); }
TEST(HausdorffBoundLong, Cow128) { (void)check("cow.off", 128); }
