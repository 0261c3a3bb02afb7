#pragma once
// The point of a triangle nearest to a point, and which feature of the
// triangle it lies on (the face's interior, one of its three edges, or one of
// its three vertices). A sphere touches a triangle where this point is closer
// than its radius; the feature tells a mesh wall which contacts of
// neighbouring triangles are the same physical contact (a sphere over a
// shared edge or vertex is nearest to that edge or vertex in each triangle).
//
// Method: the Voronoi regions of the triangle's features, tested in turn
// with the barycentric sub-determinants (Ericson, Real-Time Collision
// Detection, 2005, section 5.1.5); no square root. Degenerate triangles
// (collinear or coincident corners) are handled as their three edges, so the
// result stays finite and exact.
#include <algorithm>

#include <Eigen/Core>

namespace grains::contact {

/// The feature a closest point lies on: the face's interior, edge k (from
/// corner k to corner (k + 1) % 3), or corner k.
enum class TriangleFeature : int { Face = 0, Edge0 = 1, Edge1 = 2, Edge2 = 3, Vertex0 = 4, Vertex1 = 5, Vertex2 = 6 };

struct TrianglePoint {
  Eigen::Vector3d point;  // the nearest point of the triangle
  TriangleFeature feature;
};

/// The nearest point of the three edges (a degenerate triangle: its corners
/// collinear or coincident, so it has no face).
inline TrianglePoint closest_point_on_edges(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  auto on_segment = [&](const Eigen::Vector3d& s, const Eigen::Vector3d& e) {
    const Eigen::Vector3d d = e - s;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0 ? std::min(1.0, std::max(0.0, d.dot(p - s) / l2)) : 0.0;
    return Eigen::Vector3d(s + t * d);
  };
  const Eigen::Vector3d q0 = on_segment(a, b), q1 = on_segment(b, c), q2 = on_segment(c, a);
  const double e0 = (p - q0).squaredNorm(), e1 = (p - q1).squaredNorm(), e2 = (p - q2).squaredNorm();
  using F = TriangleFeature;
  if (e0 <= e1 && e0 <= e2) return {q0, F::Edge0};
  return e1 <= e2 ? TrianglePoint{q1, F::Edge1} : TrianglePoint{q2, F::Edge2};
}

inline TrianglePoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                               const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  using F = TriangleFeature;
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  // Degenerate (|ab x ac| below 1e-12 |ab| |ac|, i.e. the corners collinear
  // to rounding, or two of them coincident): no face, only edges.
  const double ab2 = ab.squaredNorm(), ac2 = ac.squaredNorm(), abac = ab.dot(ac);
  if (!(ab2 * ac2 - abac * abac > 1e-24 * ab2 * ac2)) return closest_point_on_edges(p, a, b, c);
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, F::Vertex0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, F::Vertex1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, F::Edge0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, F::Vertex2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, F::Edge2};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), F::Edge1};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) return closest_point_on_edges(p, a, b, c);  // rounding in a sliver
  const double denom = 1.0 / sum;
  const double v = vb * denom, w = vc * denom;
  return {a + ab * v + ac * w, F::Face};
}

}  // namespace grains::contact
