// Ellipsoid against a triangle mesh: see ellipsoid_mesh.hpp.
#include "contact/ellipsoid/ellipsoid_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "contact/ellipsoid/ellipsoid_walls.hpp"
#include "contact/ellipsoid/illinois.hpp"
#include "contact/ellipsoid/point_ellipsoid.hpp"
#include "contact/ellipsoid/surface_curvature.hpp"

namespace grains::contact {

namespace {

struct Candidate {
  int t;
  int feature;    // 0 face, 1..3 edge k - 1, 4..6 vertex k - 4
  MeshContact c;  // the contact it would give
  Vec3 ns;        // outward body normal at the point nearest to c.point (edge, vertex)
  double offset;  // face: m . a (the plane), with m = c.normal
  bool deep = false;  // a face contact in the depth measure (below)
};

// Deepest point of segment [a, b] inside the body: t in [0, 1], its depth
// and the closest surface point's normal (body frame of the ellipsoid). False
// when the segment does not enter the body.
bool deepest_on_segment(const Vec3& a, const Vec3& b, const Ellipsoid& e, const Eigen::Matrix3d& rot, double& t_best,
                        ClosestPoint& cp) {
  const Vec3 ya = rot.transpose() * (a - e.centre), d = rot.transpose() * (b - a);
  const Vec3 inv2 = e.semi_axes.cwiseProduct(e.semi_axes).cwiseInverse();
  // F(t) = (ya + t d)^T diag(inv2) (ya + t d) < 1.
  const double A = d.cwiseProduct(d).dot(inv2), B = 2 * ya.cwiseProduct(d).dot(inv2),
               C = ya.cwiseProduct(ya).dot(inv2) - 1;
  if (!(A > 0)) return false;
  const double disc = B * B - 4 * A * C;
  if (disc <= 0) return false;
  const double sq = std::sqrt(disc);
  const double q = -0.5 * (B + (B >= 0 ? sq : -sq));
  double t0 = q / A, t1 = q != 0 ? C / q : t0;
  if (t0 > t1) std::swap(t0, t1);
  const double lo = std::max(t0, 0.0), hi = std::min(t1, 1.0);
  if (!(lo < hi)) return false;
  auto at = [&](double t) { return closest_point_on_ellipsoid_body(ya + t * d, e.semi_axes); };
  auto g = [&](double t) { return at(t).normal.dot(d); };  // -D'(t), increasing
  const double glo = g(lo), ghi = g(hi);
  if (glo >= 0)
    t_best = lo;
  else if (ghi <= 0)
    t_best = hi;
  else
    t_best = illinois(g, lo, hi, glo, ghi);
  cp = at(t_best);
  cp.normal = rot * cp.normal;
  return cp.signed_distance < 0;
}

}  // namespace

int ellipsoid_mesh_contacts(const MeshSurface& mesh, const Ellipsoid& body, std::span<const std::uint32_t> tris,
                            MeshContact* out, int max) {
  thread_local std::vector<Candidate> cand;
  thread_local std::vector<MeshContact> found;
  thread_local std::vector<int> done, accepted_edges;
  cand.clear();
  const Eigen::Matrix3d rot = body.orientation.toRotationMatrix();
  const SymMat3 Q = quadratic_form(body.semi_axes, rot);
  const double scale = body.semi_axes.maxCoeff();
  const double tol = 1e-12 * scale + 4e-16 * body.centre.cwiseAbs().maxCoeff();
  const auto& V = mesh.vertices();
  const auto& F = mesh.faces();
  // The direction into triangle g, in its plane, normal to its edge (u, w).
  auto inward = [&](int g, const Vec3& u, const Vec3& w) {
    const auto& f = F[static_cast<std::size_t>(g)];
    const Vec3 dir = (w - u).normalized();
    Vec3 t = mesh.face_normal(g).cross(dir);
    Vec3 opposite = V[f[0]];
    for (int k = 0; k < 3; ++k)
      if (V[f[k]] != u && V[f[k]] != w) opposite = V[f[k]];
    if (t.dot(opposite - u) < 0) t = -t;
    return t;
  };

  for (const auto item : tris) {
    const std::uint32_t tt = item & MeshSurface::kTriangle;  // (a near list's mark is for spheres)
    const int t = static_cast<int>(tt);
    const auto& f = F[tt];
    const Vec3 &a = V[f[0]], &b = V[f[1]], &c = V[f[2]];
    Vec3 m = mesh.face_normal(t);
    if (!mesh.one_sided() && m.dot(body.centre - a) < 0) m = -m;
    bool touching = false;
    const ContactGeometry pg = ellipsoid_plane_contact(body.centre, Q, body.semi_axes, Plane{a, m}, &touching);
    if (!touching) continue;
    Candidate face{t, 0, {pg.point, pg.normal, pg.overlap, pg.radius, t, 0}, m, m.dot(a)};
    // Foot of the deepest point on the plane (ellipsoid_walls.cpp: point = deepest + overlap/2 m).
    const Vec3 foot = pg.point + 0.5 * pg.overlap * m;
    const TrianglePoint tp = closest_point_on_triangle(foot, a, b, c);
    if (tp.feature == TriangleFeature::Face || (tp.point - foot).squaredNorm() <= tol * tol) {
      cand.push_back(face);
      continue;
    }
    // The boundary's deepest point.
    double best = 0;
    Candidate edge{t, -1, {}, Vec3::Zero(), 0};
    for (int k = 0; k < 3; ++k) {
      const Vec3 &p0 = V[f[k]], &p1 = V[f[(k + 1) % 3]];
      double s;
      ClosestPoint cp;
      if (!deepest_on_segment(p0, p1, body, rot, s, cp) || -cp.signed_distance <= best) continue;
      best = -cp.signed_distance;
      const int feature = s <= 0 ? 4 + k : s >= 1 ? 4 + (k + 1) % 3 : 1 + k;
      Vec3 t1, t2;
      tangent_basis(cp.normal, t1, t2);
      const double rs = hertz_radius(curvature_tensor(Q, cp.normal, t1, t2));
      edge = {t, feature, {p0 + std::clamp(s, 0.0, 1.0) * (p1 - p0), -cp.normal, best, rs, t, feature >= 4 ? 2 : 1},
              cp.normal, 0};
    }
    if (edge.feature < 0) continue;
    // Depth growing into this triangle: its deepest point is inside it, a face contact.
    // (At a vertex it cannot: the depth falls along both edges from it.)
    bool into = false;
    if (edge.feature <= 3) {
      const int k = edge.feature - 1;
      into = edge.ns.dot(inward(t, V[f[k]], V[f[(k + 1) % 3]])) < -1e-9;
    }
    if (into) {
      // The deepest point of the triangle lies inside it, though the foot of
      // the body's deepest point does not (a penetration as deep as the
      // body's curvature radius): that point, by ascent of the depth from the
      // boundary's deepest point, a face contact in the depth measure.
      Vec3 q = edge.c.point;
      ClosestPoint cp = closest_point_on_ellipsoid(q, body);
      double step = -cp.signed_distance;
      for (int it = 0; it < 40 && step > 1e-9 * scale; ++it) {
        Vec3 up = -cp.normal;
        up -= mesh.face_normal(t) * mesh.face_normal(t).dot(up);
        if (up.norm() < 1e-12) break;
        const Vec3 trial = closest_point_on_triangle(q + up.normalized() * step, a, b, c).point;
        const ClosestPoint ct = closest_point_on_ellipsoid(trial, body);
        if (ct.signed_distance < cp.signed_distance) {
          q = trial, cp = ct;
        } else {
          step *= 0.5;
        }
      }
      Vec3 t1, t2;
      tangent_basis(cp.normal, t1, t2);
      face.c = {q, -cp.normal, -cp.signed_distance, hertz_radius(curvature_tensor(Q, cp.normal, t1, t2)), t, 0};
      face.deep = true;
    }
    cand.push_back(into ? face : edge);
  }
  if (cand.empty()) return 0;
  auto of = [&](int t) -> const Candidate* {
    const auto it = std::lower_bound(cand.begin(), cand.end(), t, [](const Candidate& c, int v) { return c.t < v; });
    return it != cand.end() && it->t == t ? &*it : nullptr;
  };
  found.clear();
  // Faces, those of one plane once (the plane measure's first; ns holds the plane's normal).
  std::vector<const Candidate*> faces;
  for (const bool deep : {false, true})
    for (const auto& c : cand) {
      if (c.feature != 0 || c.deep != deep) continue;
      bool same = false;
      for (const auto* o : faces) same = same || (o->ns.dot(c.ns) > 1 - 1e-12 && std::abs(o->offset - c.offset) <= tol);
      if (same) continue;
      faces.push_back(&c);
      found.push_back(c.c);
    }
  // Edges.
  done.clear();
  accepted_edges.clear();
  for (const auto& c : cand) {
    if (c.feature < 1 || c.feature > 3) continue;
    const int e = mesh.face_edge(c.t, c.feature - 1);
    if (std::find(done.begin(), done.end(), e) != done.end()) continue;
    done.push_back(e);
    const auto ev = mesh.edge_vertices(e);
    bool ok = true;
    for (const int g : mesh.edge_faces(e)) {
      const Candidate* cg = of(g);
      if ((cg && cg->feature == 0) || c.ns.dot(inward(g, V[ev[0]], V[ev[1]])) < -1e-9) ok = false;
    }
    if (!ok) continue;
    accepted_edges.push_back(e);
    found.push_back(c.c);
  }
  // Vertices.
  done.clear();
  for (const auto& c : cand) {
    if (c.feature < 4) continue;
    const int v = F[static_cast<std::size_t>(c.t)][static_cast<std::size_t>(c.feature - 4)];
    if (std::find(done.begin(), done.end(), v) != done.end()) continue;
    done.push_back(v);
    bool ok = true;
    for (const int g : mesh.vertex_faces(v)) {
      const Candidate* cg = of(g);
      if (cg && cg->feature == 0) ok = false;
    }
    for (const int e : mesh.vertex_edges(v)) {
      if (std::find(accepted_edges.begin(), accepted_edges.end(), e) != accepted_edges.end()) ok = false;
      const auto ev = mesh.edge_vertices(e);
      const Vec3 u = (V[static_cast<std::size_t>(ev[0] == v ? ev[1] : ev[0])] - V[static_cast<std::size_t>(v)]).normalized();
      if (c.ns.dot(u) < -1e-9) ok = false;
    }
    if (ok) found.push_back(c.c);
  }
  sort_by_depth(found);
  const int n = static_cast<int>(found.size());
  std::copy_n(found.begin(), std::min(n, max), out);
  return n;
}

}  // namespace grains::contact
