// Finer grids (label `long`): the Hausdorff bound on the bunny and the cow,
// and the bunny's ball counts at the seed's Table 2 resolutions.

#include "clump_test_data.hpp"
#include "contact/clump/ball_union.hpp"
#include "contact/clump/hausdorff.hpp"
#include "contact/clump/mesh_distance.hpp"
#include "contact/clump/sphere_decomposition.hpp"

#include <gtest/gtest.h>

using namespace grains::clump;

namespace {
void check(const std::string& name, int n) {
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
}
}  // namespace

TEST(HausdorffBoundLong, Bunny64) { check("bunny00.off", 64); }
TEST(HausdorffBoundLong, Bunny128) { check("bunny00.off", 128); }
TEST(HausdorffBoundLong, Cow64) { check("cow.off", 64); }
TEST(HausdorffBoundLong, Cow128) { check("cow.off", 128); }
