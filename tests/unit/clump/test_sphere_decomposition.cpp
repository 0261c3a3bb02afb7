// Algorithm 1: its invariants, the sphere collapsing to one ball, and the
// Hausdorff bound of Proposition 3 (with the node-covering caveat).

#include "clump_test_data.hpp"
#include "contact/clump/ball_union.hpp"
#include "contact/clump/clump_template.hpp"
#include "contact/clump/hausdorff.hpp"
#include "contact/clump/mesh_distance.hpp"
#include "contact/clump/sphere_decomposition.hpp"

#include <gtest/gtest.h>

using namespace grains::clump;

TEST(SphereDecomposition, InvariantsOfTheThreeSteps) {
  const auto m = test_mesh("cow.off");
  const MeshDistance d(m);
  const DistanceGrid g = compute_distance_grid(m, 24, &d);
  const SphereDecomposition s = decompose(g, {24, 0.25, GreedyKey::distance});
  EXPECT_NEAR(s.epsilon, std::sqrt(3.0) * half_cube_edge(m) / 24, 1e-15);
  ASSERT_GT(s.n1(), 0u);
  EXPECT_LT(s.n3(), s.n1());
  // A1 balls are inscribed: radius = distance to the surface at the centre.
  for (const Ball& b : s.a1) EXPECT_NEAR(reference_signed_distance(d, b.center), -b.radius, 1e-6);
  // Every node of X is covered by A1.
  size_t nx = 0;
  for (int k = 0; k < g.n; ++k)
    for (int j = 0; j < g.n; ++j)
      for (int i = 0; i < g.n; ++i) {
        if (g.phi[g.index(i, j, k)] > 0) continue;
        ++nx;
        bool covered = false;
        for (const Ball& b : s.a1) covered = covered || (b.center - g.node(i, j, k)).norm() <= b.radius + 1e-12;
        EXPECT_TRUE(covered) << i << " " << j << " " << k;
      }
  EXPECT_EQ(nx, s.nodes_inside);
  // S(A1) is inside S(A3): every A1 ball lies in some A3 ball (what Proposition 3 needs).
  for (const Ball& a : s.a1) {
    bool inside = false;
    for (const Ball& b : s.a3) inside = inside || (a.center - b.center).norm() <= b.radius - a.radius + 1e-12;
    EXPECT_TRUE(inside);
  }
  // A3 balls are A1 balls expanded by eps.
  for (const Ball& b : s.a3) EXPECT_NEAR(-reference_signed_distance(d, b.center) + s.epsilon, b.radius, 1e-6);
}

TEST(SphereDecomposition, SphereCollapsesToOneBallOnAnOddGrid) {
  const auto m = test_mesh("sphere.off");
  for (int n : {17, 33}) {
    const SphereDecomposition s = decompose(m, {n, 0.25, GreedyKey::distance});
    ASSERT_LE(s.n3(), 3u) << n;
    const Ball& b = s.a3.front();
    EXPECT_LT(b.center.norm(), 1e-9);
    // Inscribed radius of the 320-face polyhedron plus eps.
    EXPECT_NEAR(b.radius, MeshDistance(m).unsigned_distance({0, 0, 0}) + s.epsilon, 1e-6);
    EXPECT_GT(s.n1(), 100u);  // step 1 alone is far from a handful
  }
}

TEST(SphereDecomposition, LargerProtrusionFactorGivesFewerStepOneBalls) {
  // Table 2's trend for n1 = n2: 318, 307, 275 for mu = 0.25, 0.5, 1.
  const auto m = test_mesh("bunny00.off");
  const MeshDistance d(m);
  const DistanceGrid g = compute_distance_grid(m, 16, &d);
  const size_t n025 = decompose(g, {16, 0.25, GreedyKey::distance}).n1();
  const size_t n100 = decompose(g, {16, 1.0, GreedyKey::distance}).n1();
  const size_t n000 = decompose(g, {16, 0.0, GreedyKey::distance}).n1();
  EXPECT_GT(n000, n025);
  EXPECT_GT(n025, n100);
}

TEST(SphereDecomposition, SkeletalKeyAlsoCoversEveryNode) {
  const auto m = test_mesh("star.off");
  const MeshDistance d(m);
  const DistanceGrid g = compute_distance_grid(m, 20, &d);
  const SphereDecomposition s = decompose(g, {20, 0.25, GreedyKey::skeletal});
  for (int k = 0; k < g.n; ++k)
    for (int j = 0; j < g.n; ++j)
      for (int i = 0; i < g.n; ++i) {
        if (g.phi[g.index(i, j, k)] > 0) continue;
        bool covered = false;
        for (const Ball& b : s.a1) covered = covered || (b.center - g.node(i, j, k)).norm() <= b.radius + 1e-12;
        EXPECT_TRUE(covered);
      }
}

TEST(SphereDecomposition, RejectsBadParameters) {
  const auto m = test_mesh("cube.off");
  EXPECT_THROW(decompose(m, {1, 0.25, GreedyKey::distance}), std::invalid_argument);
  EXPECT_THROW(decompose(m, {8, 1.5, GreedyKey::distance}), std::invalid_argument);
}

namespace {

void check_hausdorff(const std::string& name, int n, bool resolved) {
  SCOPED_TRACE(name + " at N = " + std::to_string(n));
  const auto m = test_mesh(name);
  const MeshDistance d(m);
  const DistanceGrid g = compute_distance_grid(m, n, &d);
  const SphereDecomposition s = decompose(g, {n, 0.25, GreedyKey::distance});
  const BallUnion U(s.a3);
  const HausdorffResult h = measure_hausdorff(m, d, U, 0.5 * g.h, &g);
  const double eps = s.epsilon;
  // U within eps of S: guaranteed by construction (exact radii + eps).
  EXPECT_LE(h.union_to_mesh, eps * (1 + 1e-9));
  // S within delta_X of U, delta_X the covering radius of the nodes in S.
  EXPECT_LE(h.mesh_to_union, h.node_cover_radius * (1 + 1e-9) + 1e-12);
  EXPECT_LE(h.hausdorff, std::max(eps, h.node_cover_radius) * (1 + 1e-9));
  // The seed's bound itself where the grid resolves the shape. (Lemma 4's
  // delta_X <= eps fails even for the sphere, but the A1 balls reach beyond
  // the nodes, so d_H <= eps still holds there.)
  if (resolved) {
    EXPECT_LE(h.hausdorff, eps * (1 + 1e-9));
  }
  // The bound is not loose: the measurement reaches a good part of it.
  EXPECT_GT(h.hausdorff, 0.3 * eps);
}

}  // namespace

TEST(HausdorffBound, Cube) {
  for (int n : {16, 32}) check_hausdorff("cube.off", n, true);
}
TEST(HausdorffBound, Sphere) {
  for (int n : {16, 17, 32}) check_hausdorff("sphere.off", n, true);
}
TEST(HausdorffBound, Tetrahedron) {
  for (int n : {16, 32}) check_hausdorff("reference_tetrahedron.off", n, false);
}
TEST(HausdorffBound, Cow) {
  for (int n : {16, 32}) check_hausdorff("cow.off", n, false);
}
TEST(HausdorffBound, Bunny) {
  for (int n : {16, 32}) check_hausdorff("bunny00.off", n, true);
}
