// The nearest point of a triangle (contact/mesh/triangle_distance.hpp)
// against an independent exact minimum (face projection, three clamped edge
// projections, three corners), its feature, shared edges and vertices of
// neighbouring triangles, and degenerate triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tuple>

#include <Eigen/Geometry>

#include "contact/mesh/triangle_distance.hpp"

namespace grains::contact {
namespace {

using V = Eigen::Vector3d;

V on_segment(const V& p, const V& s, const V& e) {
  const V d = e - s;
  const double l2 = d.squaredNorm();
  const double t = l2 > 0 ? std::clamp(d.dot(p - s) / l2, 0.0, 1.0) : 0.0;
  return s + t * d;
}

// The minimum distance from p to the triangle, computed independently.
double exact_distance(const V& p, const V& a, const V& b, const V& c) {
  double best = std::min({(p - on_segment(p, a, b)).norm(), (p - on_segment(p, b, c)).norm(),
                          (p - on_segment(p, c, a)).norm()});
  const V n = (b - a).cross(c - a);
  if (n.squaredNorm() > 0) {
    const V q = p - n * (n.dot(p - a) / n.squaredNorm());  // projection on the plane
    // Inside when the three sub-triangles have the orientation of the triangle.
    const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                        (a - c).cross(q - c).dot(n) >= 0;
    if (inside) best = std::min(best, (p - q).norm());
  }
  return best;
}

TEST(TriangleDistance, MatchesTheExactMinimumOnRandomTrianglesAndPoints) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int features[7] = {};
  for (int trial = 0; trial < 20000; ++trial) {
    V a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    if (trial % 5 == 0) c = a + 0.999 * (b - a) + 1e-3 * V(u(rng), u(rng), u(rng));  // slivers
    const V p = 2 * V(u(rng), u(rng), u(rng));
    const TrianglePoint t = closest_point_on_triangle(p, a, b, c);
    ++features[static_cast<int>(t.feature)];
    const double d = (p - t.point).norm(), e = exact_distance(p, a, b, c);
    ASSERT_NEAR(d, e, 1e-12 * (1 + e)) << "trial " << trial;
    // The point lies on the triangle (the exact distance from it is zero).
    ASSERT_LT(exact_distance(t.point, a, b, c), 1e-12) << "trial " << trial;
  }
  for (int f = 0; f < 7; ++f) EXPECT_GT(features[f], 100) << "feature " << f << " never chosen";
}

TEST(TriangleDistance, FeaturesOfTheRegions) {
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  using F = TriangleFeature;
  EXPECT_EQ(closest_point_on_triangle(V(0.2, 0.2, 1), a, b, c).feature, F::Face);
  EXPECT_EQ(closest_point_on_triangle(V(0.5, -1, 0.3), a, b, c).feature, F::Edge0);  // a-b
  EXPECT_EQ(closest_point_on_triangle(V(1, 1, -0.2), a, b, c).feature, F::Edge1);    // b-c
  EXPECT_EQ(closest_point_on_triangle(V(-1, 0.5, 0), a, b, c).feature, F::Edge2);    // c-a
  EXPECT_EQ(closest_point_on_triangle(V(-1, -1, 0), a, b, c).feature, F::Vertex0);
  EXPECT_EQ(closest_point_on_triangle(V(2, -0.5, 0), a, b, c).feature, F::Vertex1);
  EXPECT_EQ(closest_point_on_triangle(V(-0.5, 2, 0), a, b, c).feature, F::Vertex2);
  EXPECT_LT((closest_point_on_triangle(V(0.2, 0.2, 1), a, b, c).point - V(0.2, 0.2, 0)).norm(), 1e-15);
}

TEST(TriangleDistance, NeighboursAgreeOnTheirSharedEdgeAndVertex) {
  // Two triangles folded into a ridge share the edge b-c; a point over the
  // ridge is nearest to that edge in both, at the same point: one physical
  // contact that a mesh wall must count once.
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), d(1, 1, -0.5);
  const V p(0.6, 0.6, 0.5);
  const auto t1 = closest_point_on_triangle(p, a, b, c), t2 = closest_point_on_triangle(p, b, d, c);
  EXPECT_EQ(t1.feature, TriangleFeature::Edge1);  // b-c of (a, b, c)
  EXPECT_EQ(t2.feature, TriangleFeature::Edge2);  // c-b of (b, d, c)
  EXPECT_LT((t1.point - t2.point).norm(), 1e-15);
  EXPECT_LT((t1.point - V(0.5, 0.5, 0)).norm(), 1e-15);
  // A point beyond the shared corner b is nearest to it in both.
  const V q(1.5, -0.5, -0.2);
  const auto v1 = closest_point_on_triangle(q, a, b, c), v2 = closest_point_on_triangle(q, b, d, c);
  EXPECT_EQ(v1.feature, TriangleFeature::Vertex1);
  EXPECT_EQ(v2.feature, TriangleFeature::Vertex0);
  EXPECT_EQ(v1.point, b);
  EXPECT_EQ(v2.point, b);
}

TEST(TriangleDistance, DegenerateTrianglesStayFinite) {
  const V p(0.3, 0.7, -0.2);
  for (const auto& [a, b, c] : {std::tuple{V(0, 0, 0), V(1, 0, 0), V(2, 0, 0)},   // collinear
                                std::tuple{V(0, 0, 0), V(0, 0, 0), V(1, 1, 0)},   // two corners coincide
                                std::tuple{V(1, 1, 1), V(1, 1, 1), V(1, 1, 1)}}) {  // a point
    const auto t = closest_point_on_triangle(p, a, b, c);
    ASSERT_TRUE(t.point.allFinite());
    EXPECT_NEAR((p - t.point).norm(), exact_distance(p, a, b, c), 1e-12);
  }
}

}  // namespace
}  // namespace grains::contact
