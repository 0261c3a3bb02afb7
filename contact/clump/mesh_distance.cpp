#include "contact/clump/mesh_distance.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace grains::clump {
namespace {

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection,
// 5.1.5), also returning the Voronoi feature: 0..2 vertex, 3..5 edge k-3
// (from vertex k-3 to k-2), 6 interior.
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c, int& feature) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) { feature = 0; return a; }
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) { feature = 1; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) { feature = 3; return a + d1 / (d1 - d3) * ab; }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) { feature = 2; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) { feature = 5; return a + d2 / (d2 - d6) * ac; }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    feature = 4;
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  feature = 6;
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double box_dist2(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}

// Solid angle of triangle abc seen from p (Van Oosterom & Strackee 1983).
double solid_angle(const Eigen::Vector3d& p, const Eigen::Vector3d& va, const Eigen::Vector3d& vb,
                   const Eigen::Vector3d& vc) {
  const Eigen::Vector3d a = va - p, b = vb - p, c = vc - p;
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double det = a.dot(b.cross(c));
  const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2.0 * std::atan2(det, den);
}


}  // namespace

MeshDistance::MeshDistance(const mesh::TriangleMesh& mesh) : vertices_(mesh.vertices), faces_(mesh.faces) {
  const size_t nf = faces_.size();
  face_normal_.resize(nf);
  edge_normal_.resize(nf);
  vertex_normal_.assign(vertices_.size(), Eigen::Vector3d::Zero());
  std::unordered_map<uint64_t, Eigen::Vector3d> edge_sum;
  auto key = [](int a, int b) {
    return (uint64_t(std::min(a, b)) << 32) | uint64_t(std::max(a, b));
  };
  for (size_t f = 0; f < nf; ++f) {
    const auto& t = faces_[f];
    const Eigen::Vector3d n = (vertices_[t[1]] - vertices_[t[0]]).cross(vertices_[t[2]] - vertices_[t[0]]).normalized();
    face_normal_[f] = n;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = (vertices_[t[(k + 1) % 3]] - vertices_[t[k]]).normalized();
      const Eigen::Vector3d e2 = (vertices_[t[(k + 2) % 3]] - vertices_[t[k]]).normalized();
      const double angle = std::acos(std::clamp(e1.dot(e2), -1.0, 1.0));
      vertex_normal_[t[k]] += angle * n;
      // (Eigen vectors are not zeroed by default construction.)
      edge_sum.try_emplace(key(t[k], t[(k + 1) % 3]), Eigen::Vector3d::Zero()).first->second += n;
    }
  }
  for (size_t f = 0; f < nf; ++f) {
    const auto& t = faces_[f];
    for (int k = 0; k < 3; ++k) edge_normal_[f][k] = edge_sum[key(t[k], t[(k + 1) % 3])];
  }
  order_.resize(nf);
  for (size_t i = 0; i < nf; ++i) order_[i] = static_cast<int>(i);
  nodes_.reserve(2 * nf / 4 + 2);
  if (nf > 0) {
    build(0, static_cast<int>(nf));
    build_far_field(0);
  }
}

void MeshDistance::build_far_field(int id) {
  Eigen::Vector3d area = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  double total = 0.0;
  const Node n = nodes_[id];
  if (n.left < 0) {
    for (int i = n.begin; i < n.end; ++i) {
      const auto& t = faces_[order_[i]];
      const Eigen::Vector3d a = 0.5 * (vertices_[t[1]] - vertices_[t[0]]).cross(vertices_[t[2]] - vertices_[t[0]]);
      const double w = a.norm();
      area += a;
      moment += w * (vertices_[t[0]] + vertices_[t[1]] + vertices_[t[2]]) / 3.0;
      total += w;
    }
  } else {
    build_far_field(n.left);
    build_far_field(n.right);
    for (int c : {n.left, n.right}) {
      const Node& k = nodes_[c];
      area += k.area_vector;
      moment += k.area * k.centroid;
      total += k.area;
    }
  }
  Node& m = nodes_[id];
  m.area_vector = area;
  m.area = total;
  m.centroid = total > 0.0 ? Eigen::Vector3d(moment / total) : Eigen::Vector3d(0.5 * (m.lo + m.hi));
  // Radius of a sphere about the centroid holding the node's box.
  m.radius = (m.lo - m.centroid).cwiseAbs().cwiseMax((m.hi - m.centroid).cwiseAbs()).norm();
}

int MeshDistance::build(int begin, int end) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  Eigen::Vector3d clo = lo, chi = hi;
  for (int i = begin; i < end; ++i) {
    const auto& t = faces_[order_[i]];
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : t) {
      lo = lo.cwiseMin(vertices_[v]);
      hi = hi.cwiseMax(vertices_[v]);
      c += vertices_[v] / 3.0;
    }
    clo = clo.cwiseMin(c);
    chi = chi.cwiseMax(c);
  }
  nodes_[id].lo = lo;
  nodes_[id].hi = hi;
  if (end - begin <= 4) {
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    return id;
  }
  int axis;
  (chi - clo).maxCoeff(&axis);
  const int mid = (begin + end) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int f, int g) {
    const auto& a = faces_[f];
    const auto& b = faces_[g];
    return vertices_[a[0]][axis] + vertices_[a[1]][axis] + vertices_[a[2]][axis] <
           vertices_[b[0]][axis] + vertices_[b[1]][axis] + vertices_[b[2]][axis];
  });
  const int l = build(begin, mid);
  const int r = build(mid, end);
  nodes_[id].left = l;
  nodes_[id].right = r;
  return id;
}

MeshDistance::Hit MeshDistance::closest(const Eigen::Vector3d& p, double bound2) const {
  Hit best{bound2, -1, 6, p};
  if (nodes_.empty()) return best;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (box_dist2(p, n.lo, n.hi) >= best.dist2) continue;
    if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) {
        const int f = order_[i];
        const auto& t = faces_[f];
        int feature = 6;
        const Eigen::Vector3d q = closest_on_triangle(p, vertices_[t[0]], vertices_[t[1]], vertices_[t[2]], feature);
        const double d2 = (q - p).squaredNorm();
        if (d2 < best.dist2) best = {d2, f, feature, q};
      }
      continue;
    }
    const double dl = box_dist2(p, nodes_[n.left].lo, nodes_[n.left].hi);
    const double dr = box_dist2(p, nodes_[n.right].lo, nodes_[n.right].hi);
    // Push the farther child first so the nearer one is visited first.
    if (dl < dr) {
      stack[top++] = n.right;
      stack[top++] = n.left;
    } else {
      stack[top++] = n.left;
      stack[top++] = n.right;
    }
  }
  return best;
}

double MeshDistance::unsigned_distance(const Eigen::Vector3d& p) const {
  return std::sqrt(closest(p, std::numeric_limits<double>::infinity()).dist2);
}

double MeshDistance::signed_distance(const Eigen::Vector3d& p) const {
  const Hit h = closest(p, std::numeric_limits<double>::infinity());
  return sign_of(h, p) * std::sqrt(h.dist2);
}

double MeshDistance::signed_distance(const Eigen::Vector3d& p, double bound) const {
  Hit h = closest(p, bound * bound);
  if (h.face < 0) h = closest(p, std::numeric_limits<double>::infinity());  // the guess was too small
  return sign_of(h, p) * std::sqrt(h.dist2);
}

double MeshDistance::winding_number(const Eigen::Vector3d& p) const {
  // Van Oosterom & Strackee (1983): tan(Omega / 2) = det[a b c] /
  // (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|), a, b, c the corners relative to p.
  double sum = 0.0;
  for (const auto& t : faces_) sum += solid_angle(p, vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]);
  return sum / (4.0 * M_PI);
}

double MeshDistance::winding_number_fast(const Eigen::Vector3d& p, double beta) const {
  if (nodes_.empty()) return 0.0;
  double sum = 0.0;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    const Eigen::Vector3d r = n.centroid - p;
    const double d2 = r.squaredNorm();
    if (d2 > beta * beta * n.radius * n.radius) {
      sum += r.dot(n.area_vector) / (d2 * std::sqrt(d2));
      continue;
    }
    if (n.left < 0) {
      for (int i = n.begin; i < n.end; ++i) {
        const auto& t = faces_[order_[i]];
        sum += solid_angle(p, vertices_[t[0]], vertices_[t[1]], vertices_[t[2]]);
      }
      continue;
    }
    stack[top++] = n.left;
    stack[top++] = n.right;
  }
  return sum / (4.0 * M_PI);
}

double MeshDistance::sign_of(const Hit& h, const Eigen::Vector3d& p) const {
  if (h.face < 0) return 1.0;
  Eigen::Vector3d n;
  if (h.feature == 6) {
    n = face_normal_[h.face];
  } else if (h.feature >= 3) {
    n = edge_normal_[h.face][h.feature - 3];
  } else {
    n = vertex_normal_[faces_[h.face][h.feature]];
  }
  return (p - h.point).dot(n) >= 0.0 ? 1.0 : -1.0;
}

}  // namespace grains::clump
