#include "contact/mesh/mesh_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace grains::contact {

namespace {

// The CSR lists of `lists` (start offsets and items).
void to_csr(const std::vector<std::vector<int>>& lists, std::vector<int>& start, std::vector<int>& items) {
  start.assign(lists.size() + 1, 0);
  for (std::size_t k = 0; k < lists.size(); ++k) start[k + 1] = start[k] + static_cast<int>(lists[k].size());
  items.clear();
  items.reserve(static_cast<std::size_t>(start.back()));
  for (const auto& l : lists) items.insert(items.end(), l.begin(), l.end());
}

double box_distance2(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double e = std::max({lo[k] - x[k], 0.0, x[k] - hi[k]});
    d2 += e * e;
  }
  return d2;
}

constexpr int kLeaf = 8;

struct Candidate {
  int t;
  TriangleFeature f;
  Vec3 q;
  double d2;
};

}  // namespace

namespace {
// Deepest first, stable: an insertion sort (a few contacts, no allocation).
void sort_deepest_first(MeshContact* c, std::size_t n) {
  for (std::size_t i = 1; i < n; ++i)
    for (std::size_t j = i; j > 0 && c[j].depth > c[j - 1].depth; --j) std::swap(c[j], c[j - 1]);
}
}  // namespace

void sort_by_depth(std::vector<MeshContact>& c) { sort_deepest_first(c.data(), c.size()); }

MeshSurface::MeshSurface(std::vector<Vec3> vertices, std::vector<std::array<int, 3>> faces, bool one_sided)
    : vertices_(std::move(vertices)), faces_(std::move(faces)), one_sided_(one_sided) {
  const std::size_t nf = faces_.size(), nv = vertices_.size();
  screen_.resize(nf);
  face_edge_.resize(nf);
  std::unordered_map<std::uint64_t, int> edge_id;
  edge_id.reserve(3 * nf / 2 + 1);
  std::vector<std::vector<int>> edge_faces, vertex_faces(nv), vertex_edges(nv);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& t = faces_[f];
    const Vec3 n = (vertices_[t[1]] - vertices_[t[0]]).cross(vertices_[t[2]] - vertices_[t[0]]);
    Screen& sc = screen_[f];
    sc.n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3(0, 0, 1);
    sc.off = sc.n.dot(vertices_[t[0]]);
    sc.a = vertices_[t[0]];
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = vertices_[t[k]];
      const Vec3 m = sc.n.cross(vertices_[t[(k + 1) % 3]] - a).normalized();  // counter-clockwise: inwards
      sc.e[k] = {m, m.dot(a)};
    }
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::uint32_t(std::max(a, b));
      auto [it, fresh] = edge_id.try_emplace(key, static_cast<int>(edge_vertex_.size()));
      if (fresh) {
        edge_vertex_.push_back({std::min(a, b), std::max(a, b)});
        edge_faces.emplace_back();
        vertex_edges[static_cast<std::size_t>(a)].push_back(it->second);
        vertex_edges[static_cast<std::size_t>(b)].push_back(it->second);
      }
      face_edge_[f][static_cast<std::size_t>(k)] = it->second;
      edge_faces[static_cast<std::size_t>(it->second)].push_back(static_cast<int>(f));
      vertex_faces[static_cast<std::size_t>(a)].push_back(static_cast<int>(f));
    }
  }
  for (const auto& l : edge_faces) {
    boundary_edges_ += l.size() == 1;
    nonmanifold_edges_ += l.size() > 2;
  }
  to_csr(edge_faces, edge_face_start_, edge_face_);
  to_csr(vertex_faces, vertex_face_start_, vertex_face_);
  to_csr(vertex_edges, vertex_edge_start_, vertex_edge_);

  // The hierarchy: median splits along the longest extent of the centroids.
  std::vector<Vec3> centroid(nf);
  for (std::size_t f = 0; f < nf; ++f)
    centroid[f] = (vertices_[faces_[f][0]] + vertices_[faces_[f][1]] + vertices_[faces_[f][2]]) / 3.0;
  order_.resize(nf);
  std::iota(order_.begin(), order_.end(), 0);
  nodes_.reserve(2 * nf);
  if (nf > 0) build(0, static_cast<int>(nf), centroid, 0);
  nodes_.shrink_to_fit();
  if (!nodes_.empty()) lo_ = nodes_[0].lo, hi_ = nodes_[0].hi;
}

int MeshSurface::build(int begin, int end, const std::vector<Vec3>& centroid, int depth) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Vec3 clo = lo, chi = hi;
  for (int k = begin; k < end; ++k) {
    const auto& t = faces_[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])];
    for (int c = 0; c < 3; ++c) {
      lo = lo.cwiseMin(vertices_[t[c]]);
      hi = hi.cwiseMax(vertices_[t[c]]);
    }
    clo = clo.cwiseMin(centroid[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])]);
    chi = chi.cwiseMax(centroid[static_cast<std::size_t>(order_[static_cast<std::size_t>(k)])]);
  }
  nodes_[static_cast<std::size_t>(id)].lo = lo;
  nodes_[static_cast<std::size_t>(id)].hi = hi;
  if (end - begin <= kLeaf) {
    nodes_[static_cast<std::size_t>(id)].first = begin;
    nodes_[static_cast<std::size_t>(id)].count = end - begin;
    return id;
  }
  // Split at the middle of the centroids' extent along its longest axis, so
  // that parts of the mesh far apart (a vessel and a blade, a box and a
  // plate beside it) part at the top of the hierarchy; the median when that
  // leaves one side empty, and below depth 32 (the depth stays under
  // 32 + log2(triangles): near()'s stack of 64).
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const double cut = 0.5 * (clo[axis] + chi[axis]);
  const auto less = [&](int a, int b) {
    const double ca = centroid[static_cast<std::size_t>(a)][axis], cb = centroid[static_cast<std::size_t>(b)][axis];
    return ca < cb || (ca == cb && a < b);
  };
  auto split = std::partition(order_.begin() + begin, order_.begin() + end,
                              [&](int t) { return centroid[static_cast<std::size_t>(t)][axis] < cut; });
  int mid = static_cast<int>(split - order_.begin());
  if (mid == begin || mid == end || depth >= 32) {
    mid = (begin + end) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, less);
  }
  const int left = build(begin, mid, centroid, depth + 1);
  const int right = build(mid, end, centroid, depth + 1);
  nodes_[static_cast<std::size_t>(id)].left = left;
  nodes_[static_cast<std::size_t>(id)].right = right;
  return id;
}

std::size_t MeshSurface::bytes() const {
  return vertices_.capacity() * sizeof(Vec3) + faces_.capacity() * sizeof(faces_[0]) +
         screen_.capacity() * sizeof(Screen) +
         face_edge_.capacity() * sizeof(face_edge_[0]) +
         edge_vertex_.capacity() * sizeof(edge_vertex_[0]) +
         (edge_face_start_.capacity() + edge_face_.capacity() + vertex_face_start_.capacity() +
          vertex_face_.capacity() + vertex_edge_start_.capacity() + vertex_edge_.capacity() + order_.capacity()) *
             sizeof(int) +
         nodes_.capacity() * sizeof(Node);
}

void MeshSurface::near(const Vec3& x, double reach, std::vector<std::uint32_t>& out, std::size_t* visited,
                       double skin) const {
  if (nodes_.empty()) return;
  const double r2 = reach * reach;
  // Deep: inside each edge's line by more than the skin, and by more than
  // the dot products' rounding (a few ulps of |x|), so that a centre moved
  // by up to the skin is still inside as the screen computes it.
  const double deep = skin >= 0 ? skin + 1e-12 * (x.cwiseAbs().maxCoeff() + reach) : std::numeric_limits<double>::infinity();
  const std::size_t first = out.size();
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  std::size_t seen = 0;
  while (top > 0) {
    const Node& nd = nodes_[static_cast<std::size_t>(stack[--top])];
    ++seen;
    if (box_distance2(x, nd.lo, nd.hi) >= r2) continue;
    if (nd.count > 0) {
      for (int k = nd.first; k < nd.first + nd.count; ++k) {
        const int t = order_[static_cast<std::size_t>(k)];
        // The screen of sphere_contacts: the plane, then the edges' lines
        // (over the face, the distance is the plane's; outside, the
        // distance from the nearest line bounds it from below).
        const Screen& sc = screen_[static_cast<std::size_t>(t)];
        const double h = sc.n.dot(x) - sc.off;
        if (h * h >= r2) continue;  // beyond reach of its plane
        const double out_by = std::max({sc.e[0].w() - sc.e[0].dot(x), sc.e[1].w() - sc.e[1].dot(x),
                                        sc.e[2].w() - sc.e[2].dot(x)});
        if (out_by <= 0) {
          out.push_back(static_cast<std::uint32_t>(t) | (-out_by > deep ? kDeep : 0u));
          continue;
        }
        if (out_by * out_by + h * h >= r2) continue;
        const auto& f = faces_[static_cast<std::size_t>(t)];
        const TrianglePoint tp = closest_point_on_triangle(x, vertices_[f[0]], vertices_[f[1]], vertices_[f[2]]);
        if ((x - tp.point).squaredNorm() < r2) out.push_back(static_cast<std::uint32_t>(t));
      }
    } else {
      stack[top++] = nd.left;
      stack[top++] = nd.right;
    }
  }
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
            [](std::uint32_t a, std::uint32_t b) { return (a & kTriangle) < (b & kTriangle); });
  if (visited) *visited += seen;
}

double MeshSurface::distance(const Vec3& x, double limit) const {
  thread_local std::vector<std::uint32_t> tris;
  tris.clear();
  near(x, limit, tris);
  double best = std::numeric_limits<double>::infinity();
  for (const auto t : tris) {
    const auto& f = faces_[t];
    best = std::min(best, (x - closest_point_on_triangle(x, vertices_[f[0]], vertices_[f[1]], vertices_[f[2]]).point).norm());
  }
  return best;
}

int MeshSurface::resolve_sphere(const Vec3& x, double r, std::span<const std::uint32_t> tris, MeshContact* out,
                                int max) const {
  const int n = resolve_by_planes(x, r, tris, out, max);
  return n >= 0 ? n : resolve_rule(x, r, tris, out, max);
}

int MeshSurface::resolve_by_planes(const Vec3& x, double r, std::span<const std::uint32_t> tris, MeshContact* out,
                                   int max) const {
  // The triangles within r, from their planes as sphere_screen reads them:
  // those whose face the centre is over, and those it is outside of across
  // one edge's line only (inside or on the other two): their nearest point
  // is on that edge, ends included (the region beyond one edge, between the
  // other two edges' lines, projects onto the closed edge).
  constexpr int kMax = 8;
  int over[kMax], beyond[kMax];
  int n_over = 0, n_beyond = 0;
  const double r2 = r * r;
  for (const auto item : tris) {
    const std::uint32_t t = item & kTriangle;
    const Screen& sc = screen_[t];
    const double h = sc.n.dot(x) - sc.off;
    if (h * h >= r2) continue;
    if (item & kDeep) {
      if (n_over == kMax) return -1;
      over[n_over++] = static_cast<int>(t);
      continue;
    }
    const double s[3] = {sc.e[0].dot(x) - sc.e[0].w(), sc.e[1].dot(x) - sc.e[1].w(), sc.e[2].dot(x) - sc.e[2].w()};
    const double out_by = std::max({-s[0], -s[1], -s[2]});
    if (out_by > 0 && out_by * out_by + h * h >= r2) continue;
    if (out_by < 0) {
      if (n_over == kMax) return -1;
      over[n_over++] = static_cast<int>(t);
      continue;
    }
    // Outside (or on) an edge's line: across exactly one edge, which has one
    // other face, else the full rule.
    const int k = s[0] < 0 ? 0 : s[1] < 0 ? 1 : 2;
    if (!(s[k] < 0) || s[(k + 1) % 3] < 0 || s[(k + 2) % 3] < 0) return -1;
    const auto faces = edge_faces(face_edge_[t][static_cast<std::size_t>(k)]);
    if (faces.size() != 2 || n_beyond == kMax) return -1;
    beyond[n_beyond++] = faces[0] == static_cast<int>(t) ? faces[1] : faces[0];
  }
  // A triangle nearest on an edge it shares with a triangle whose face the
  // centre is over gives no contact (the rule: that edge, and its ends, are
  // not nearest for every face that shares them); the faces give theirs.
  if (n_over == 0) return -1;
  for (int b = 0; b < n_beyond; ++b)
    if (std::find(over, over + n_over, beyond[b]) == over + n_over) return -1;
  MeshContact found[kMax];
  int n = 0;
  for (int k = 0; k < n_over; ++k) {
    if (face_contact(x, r, over[k], found[n])) ++n;  // a graze at r (the plane's offset rounds differently) is none
  }
  sort_deepest_first(found, static_cast<std::size_t>(n));
  std::copy_n(found, std::min(n, max), out);
  return n;
}

int MeshSurface::resolve_rule(const Vec3& x, double r, std::span<const std::uint32_t> tris, MeshContact* out,
                              int max) const {
  struct Scratch {
    std::vector<Candidate> cand;
    std::vector<MeshContact> found;
    std::vector<int> done_edges, done_vertices, accepted_edges;
  };
  thread_local Scratch scratch;
  auto& [cand, found, done_edges, done_vertices, accepted_edges] = scratch;
  cand.clear();
  const double r2 = r * r;
  for (const auto item : tris) {
    const std::uint32_t t = item & kTriangle;
    const auto& f = faces_[t];
    const Vec3& a = vertices_[f[0]];
    const double h = screen_[t].n.dot(x - a);
    if (h * h >= r2) continue;  // its plane is beyond the radius
    const TrianglePoint tp = closest_point_on_triangle(x, a, vertices_[f[1]], vertices_[f[2]]);
    const double d2 = (x - tp.point).squaredNorm();
    if (d2 < r2) cand.push_back({static_cast<int>(t), tp.feature, tp.point, d2});
  }
  if (cand.empty()) return 0;
  found.clear();
  // The candidate of triangle t (tris ascending, so cand is too), or null.
  auto of = [&](int t) -> const Candidate* {
    const auto it = std::lower_bound(cand.begin(), cand.end(), t, [](const Candidate& c, int v) { return c.t < v; });
    return it != cand.end() && it->t == t ? &*it : nullptr;
  };
  const double tol = 1e-12 * r + 4e-16 * x.cwiseAbs().maxCoeff();
  const double tol2 = tol * tol;
  auto towards = [&](const Candidate& c) {  // unit normal from the point to the centre
    const double d = std::sqrt(c.d2);
    if (d > tol) return Vec3((x - c.q) / d);
    const Vec3& n = screen_[static_cast<std::size_t>(c.t)].n;  // the centre on the surface
    return n.dot(x - vertices_[faces_[static_cast<std::size_t>(c.t)][0]]) >= 0 || one_sided_ ? n : Vec3(-n);
  };
  auto in_front = [&](int t, const Vec3& q) { return screen_[static_cast<std::size_t>(t)].n.dot(x - q) >= 0; };

  // Faces: the plane's contact, as a plane wall computes it (normal, the
  // centre's distance, its foot), with the normal towards the centre unless
  // one-sided; none where face_touches says it does not touch (the
  // nearest point's distance and the plane's round differently at r).
  for (const auto& c : cand) {
    if (c.f != TriangleFeature::Face) continue;
    found.emplace_back();
    if (!face_contact(x, r, c.t, found.back())) found.pop_back();
  }
  // Edges: one contact per edge, when it is the local minimum for all its faces.
  done_edges.clear();
  accepted_edges.clear();
  for (const auto& c : cand) {
    const int fk = static_cast<int>(c.f);
    if (fk < 1 || fk > 3) continue;
    const int e = face_edge_[static_cast<std::size_t>(c.t)][static_cast<std::size_t>(fk - 1)];
    if (std::find(done_edges.begin(), done_edges.end(), e) != done_edges.end()) continue;
    done_edges.push_back(e);
    bool ok = true, front = !one_sided_;
    for (int k = edge_face_start_[static_cast<std::size_t>(e)]; ok && k < edge_face_start_[static_cast<std::size_t>(e) + 1]; ++k) {
      const int g = edge_face_[static_cast<std::size_t>(k)];
      front = front || in_front(g, c.q);
      const Candidate* cg = of(g);
      if (!cg) continue;  // beyond the radius (rounding): no nearer point there
      const int gk = static_cast<int>(cg->f);
      const bool same_edge = gk >= 1 && gk <= 3 && face_edge_[static_cast<std::size_t>(g)][static_cast<std::size_t>(gk - 1)] == e;
      if (cg->f == TriangleFeature::Face || !(same_edge || (cg->q - c.q).squaredNorm() <= tol2)) ok = false;
    }
    if (!ok || !front) continue;
    accepted_edges.push_back(e);
    found.push_back({c.q, towards(c), r - std::sqrt(c.d2), r, c.t, 1});
  }
  // Vertices: one contact per vertex, when it is the local minimum for all its faces.
  done_vertices.clear();
  for (const auto& c : cand) {
    const int fk = static_cast<int>(c.f);
    if (fk < 4) continue;
    const int v = faces_[static_cast<std::size_t>(c.t)][static_cast<std::size_t>(fk - 4)];
    if (std::find(done_vertices.begin(), done_vertices.end(), v) != done_vertices.end()) continue;
    done_vertices.push_back(v);
    bool ok = true, front = !one_sided_;
    for (int k = vertex_edge_start_[static_cast<std::size_t>(v)]; ok && k < vertex_edge_start_[static_cast<std::size_t>(v) + 1]; ++k)
      if (std::find(accepted_edges.begin(), accepted_edges.end(), vertex_edge_[static_cast<std::size_t>(k)]) !=
          accepted_edges.end())
        ok = false;
    for (int k = vertex_face_start_[static_cast<std::size_t>(v)]; ok && k < vertex_face_start_[static_cast<std::size_t>(v) + 1]; ++k) {
      const int g = vertex_face_[static_cast<std::size_t>(k)];
      front = front || in_front(g, c.q);
      const Candidate* cg = of(g);
      if (!cg) continue;
      const int gk = static_cast<int>(cg->f);
      const bool same_vertex = gk >= 4 && faces_[static_cast<std::size_t>(g)][static_cast<std::size_t>(gk - 4)] == v;
      if (cg->f == TriangleFeature::Face || !(same_vertex || (cg->q - c.q).squaredNorm() <= tol2)) ok = false;
    }
    if (!ok || !front) continue;
    found.push_back({c.q, towards(c), r - std::sqrt(c.d2), r, c.t, 2});
  }
  sort_by_depth(found);
  const int n = static_cast<int>(found.size());
  std::copy_n(found.begin(), std::min(n, max), out);
  return n;
}

}  // namespace grains::contact
