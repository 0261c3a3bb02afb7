#pragma once
// A triangle mesh as a wall surface: its topology (each edge's faces, each
// vertex's faces and edges), a bounding-volume hierarchy over its triangles,
// and the contacts of a sphere with it, one per physical contact.
//
// One contact per physical contact. A sphere over the edge shared by two
// triangles is nearest to that edge in both; over a vertex shared by six
// triangles, nearest to it in all six. The rule (the nearest point must be a
// local minimum of the distance over the surface):
//   - a triangle whose nearest point is inside its face gives a contact;
//   - an edge gives one contact when every triangle that shares it is nearest
//     at that edge (its nearest point is on the edge, or at the same point);
//     none when any of them is nearest inside its face;
//   - a vertex gives one contact when every triangle that shares it is
//     nearest at that vertex; none when any is nearest inside its face or an
//     edge through the vertex already gave the contact.
// On a flat or smooth patch that is the one contact a plane would give,
// continuous as a sphere rolls across edges and vertices; at a convex ridge
// or corner, the contact with the edge or vertex; in a concave valley or
// corner, one contact with each face. No angular tolerance is involved: only
// the feature each triangle reports (contact/mesh/triangle_distance.hpp) and,
// for ties, whether two nearest points coincide to 1e-12 of the radius.
//
// Two-sided by default: the normal points from the contact point to the
// centre. One-sided: a face pushes along its outward (counter-clockwise)
// normal even when the centre has passed behind it (up to a radius), and
// edges and vertices only touch from in front of one of their faces.
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "contact/contact_geometry.hpp"
#include "contact/mesh/triangle_distance.hpp"

namespace grains::contact {

/// One contact of a sphere with a mesh surface (in the mesh's frame).
struct MeshContact {
  Vec3 point;       // nearest point of the surface
  Vec3 normal;      // unit, from the surface towards the sphere's centre
  double depth;     // r - distance (> 0)
  double radius;    // R* for the Hertz law
  int triangle;     // a triangle that holds the point
  int feature;      // 0 face, 1 edge, 2 vertex
};

/// Contacts deepest first, in place (stable; no allocation).
void sort_by_depth(std::vector<MeshContact>& c);

class MeshSurface {
 public:
  MeshSurface() = default;
  /// Faces index vertices; degenerate faces must have been removed.
  MeshSurface(std::vector<Vec3> vertices, std::vector<std::array<int, 3>> faces, bool one_sided);

  std::size_t triangles() const { return faces_.size(); }
  std::size_t edges() const { return edge_vertex_.size(); }
  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<std::array<int, 3>>& faces() const { return faces_; }
  const Vec3& face_normal(int t) const { return screen_[static_cast<std::size_t>(t)].n; }
  bool one_sided() const { return one_sided_; }
  Vec3 bbox_min() const { return lo_; }
  Vec3 bbox_max() const { return hi_; }
  /// Edges used by one face (an open mesh's rim) and by more than two.
  std::size_t boundary_edges() const { return boundary_edges_; }
  std::size_t nonmanifold_edges() const { return nonmanifold_edges_; }
  // Topology: edge k of face t runs from corner k to corner k + 1.
  int face_edge(int t, int k) const { return face_edge_[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)]; }
  std::span<const int> edge_faces(int e) const { return csr(edge_face_start_, edge_face_, e); }
  std::span<const int> vertex_faces(int v) const { return csr(vertex_face_start_, vertex_face_, v); }
  std::span<const int> vertex_edges(int v) const { return csr(vertex_edge_start_, vertex_edge_, v); }
  const std::array<int, 2>& edge_vertices(int e) const { return edge_vertex_[static_cast<std::size_t>(e)]; }
  /// Bytes held (vertices, faces, topology, hierarchy).
  std::size_t bytes() const;

  /// Appends the triangles within `reach` of x (exact distance), in
  /// ascending order; `visited` counts the hierarchy nodes looked at.
  /// With a `skin` (>= 0), a triangle whose face x is over by more than the
  /// skin from each of its edges' lines is appended as t | kDeep: a wall's
  /// near list for a sphere that moves less than the skin before the next
  /// build stays over that face, so sphere_screen need not test its edges.
  void near(const Vec3& x, double reach, std::vector<std::uint32_t>& out, std::size_t* visited = nullptr,
            double skin = -1) const;
  /// A near-list item: a triangle, with kDeep when marked (near()).
  static constexpr std::uint32_t kDeep = 1u << 31, kTriangle = kDeep - 1;
  /// Distance from x to the nearest triangle (infinity when there is none within `limit`).
  double distance(const Vec3& x, double limit) const;

  /// The contacts of sphere (x, r) with the triangles `tris` (a superset of
  /// those within r; items of near(), marked or not), one per physical contact, deepest first; at most `max`
  /// written to out; returns how many there are (may exceed max).
  /// The common case (no other triangle within r, or none at all) is
  /// settled here, inline; the rest in resolve_sphere.
  GRAINS_INLINE int sphere_contacts(const Vec3& x, double r, std::span<const std::uint32_t> tris, MeshContact* out,
                                    int max) const {
    const int t = sphere_screen(x, r, tris);
    if (t == kNone) return 0;
    if (t < 0 || max < 1) return resolve_sphere(x, r, tris, out, max);
    return face_contact(x, r, t, out[0]) ? 1 : 0;
  }
  static constexpr int kNone = -1, kResolve = -2;
  /// The screen of sphere_contacts: kNone when no triangle of `tris` is
  /// within r of x; a triangle when x is over its face and no other is within
  /// r (its contact is the face's, face_normal, when face_touches says so);
  /// kResolve otherwise (several triangles, or an edge or a vertex:
  /// resolve_sphere decides). A list of one deep item (near(): x stays over
  /// that face until the next build, and no other triangle was within
  /// reach) is that triangle at once: its plane alone decides.
  GRAINS_INLINE int sphere_screen(const Vec3& x, double r, std::span<const std::uint32_t> tris) const {
    if (tris.size() == 1 && (tris[0] & kDeep)) return static_cast<int>(tris[0] & kTriangle);
    const double r2 = r * r;
    int hit = kNone;
    bool inside = false;
    for (const auto item : tris) {
      const std::uint32_t t = item & kTriangle;
      const Screen& sc = screen_[t];
      const double h = sc.n.dot(x) - sc.off;  // signed distance from its plane
      if (h * h >= r2) continue;             // its plane is beyond the radius
      if (item & kDeep) {  // x still over the face (near()): what the edges' lines would say
        if (hit >= 0) return kResolve;
        hit = static_cast<int>(t);
        inside = true;
        continue;
      }
      // The distances of x from the lines of the three edges, in the plane
      // (positive inside): all positive, x is over the face; the largest
      // outside bounds the distance from the triangle from below.
      const double s0 = sc.e[0].dot(x) - sc.e[0].w(), s1 = sc.e[1].dot(x) - sc.e[1].w(),
                   s2 = sc.e[2].dot(x) - sc.e[2].w();
      const double out_by = std::max({-s0, -s1, -s2});
      if (out_by > 0 && out_by * out_by + h * h >= r2) continue;
      if (hit >= 0) return kResolve;  // several: the full rule
      hit = static_cast<int>(t);
      inside = out_by < 0;
    }
    return hit >= 0 && !inside ? kResolve : hit;
  }
  /// The contacts of sphere (x, r) with `tris` by the full rule (faces,
  /// edges, vertices), as sphere_contacts returns them: resolve_by_planes
  /// when it settles them, else resolve_rule.
  int resolve_sphere(const Vec3& x, double r, std::span<const std::uint32_t> tris, MeshContact* out, int max) const;
  /// The cases the screen sends on that the triangles' planes settle: the
  /// centre over the faces of one or more triangles within r (a concave
  /// valley or corner: a contact with each face), and every other triangle
  /// within r outside one edge's line only, that edge shared with one of
  /// those faces (a quad's diagonal, a bend: by the rule, no contact of its
  /// own). The contacts as resolve_rule gives them, or -1 when it cannot tell
  /// (an edge or a vertex may touch).
  int resolve_by_planes(const Vec3& x, double r, std::span<const std::uint32_t> tris, MeshContact* out, int max) const;
  /// The full rule, from each triangle's nearest point and feature.
  int resolve_rule(const Vec3& x, double r, std::span<const std::uint32_t> tris, MeshContact* out, int max) const;
  /// The face contact of face_contact as a normal n (towards x unless
  /// one-sided) and the centre's distance s along it: the foot is x - n s.
  GRAINS_INLINE void face_normal(const Vec3& x, int t, Vec3& n, double& s) const {
    const Screen& sc = screen_[static_cast<std::size_t>(t)];
    const Vec3& n0 = sc.n;
    const Vec3& a = sc.a;
    // One dot product: with -n0 each product, and so the sum, is exactly
    // the negated one (rounding is symmetric in sign).
    const double d = n0.dot(x - a);
    const bool front = one_sided_ || d >= 0;
    n = front ? n0 : Vec3(-n0);
    s = front ? d : -d;
  }
  /// Whether a sphere of radius r whose centre is at distance s along a
  /// face's normal (face_normal) touches its plane: |s| < r (one-sided, s
  /// may be negative: the centre behind the face, up to r). (The screen's
  /// plane offset rounds differently: a graze at r may pass it.)
  static GRAINS_INLINE bool face_touches(double s, double r) { return std::abs(s) < r; }
  /// The contact of sphere (x, r) with the face of triangle t: the plane's,
  /// as a plane wall computes it (normal towards the centre unless
  /// one-sided, the centre's distance, its foot), written to out; returns
  /// whether it touches (face_touches: a graze at r, or a one-sided face
  /// the centre is a radius or more behind, is none).
  GRAINS_INLINE bool face_contact(const Vec3& x, double r, int t, MeshContact& out) const {
    Vec3 n;
    double s;
    face_normal(x, t, n, s);
    out = {Vec3(x - n * s), n, r - s, r, t, 0};
    return face_touches(s, r);
  }

 private:
  struct Node {
    Vec3 lo, hi;
    int first = 0, count = 0;  // a leaf's triangles: order_[first, first + count)
    int left = -1, right = -1; // an inner node's children (count = 0)
  };
  int build(int begin, int end, const std::vector<Vec3>& centroid, int depth);
  static std::span<const int> csr(const std::vector<int>& start, const std::vector<int>& items, int k) {
    const auto b = static_cast<std::size_t>(start[static_cast<std::size_t>(k)]);
    const auto e = static_cast<std::size_t>(start[static_cast<std::size_t>(k) + 1]);
    return {items.data() + b, e - b};
  }

  std::vector<Vec3> vertices_;
  std::vector<std::array<int, 3>> faces_;
  struct EdgePlane {                             // unit in-plane normal of an edge, into the face, and its offset
    Vec3 m;
    double off;
    double dot(const Vec3& x) const { return m.dot(x); }
    double w() const { return off; }
  };
  // A triangle's planes, in one place (what the common case reads): its unit
  // normal (counter-clockwise) and plane offset, its edges' in-plane normals
  // and offsets, and its corner 0 (face_normal's distance is taken from it:
  // no lookup through faces_ and vertices_). 152 bytes, 192 as aligned.
  struct alignas(64) Screen {
    Vec3 n;
    double off;
    EdgePlane e[3];
    Vec3 a;
  };
  std::vector<Screen> screen_;
  std::vector<std::array<int, 3>> face_edge_;    // edge k runs from corner k to corner k + 1
  std::vector<std::array<int, 2>> edge_vertex_;  // endpoints
  std::vector<int> edge_face_start_, edge_face_;       // faces of each edge (CSR)
  std::vector<int> vertex_face_start_, vertex_face_;   // faces of each vertex (CSR)
  std::vector<int> vertex_edge_start_, vertex_edge_;   // edges of each vertex (CSR)
  std::vector<Node> nodes_;
  std::vector<int> order_;  // triangles in leaf order
  Vec3 lo_{0, 0, 0}, hi_{0, 0, 0};
  std::size_t boundary_edges_ = 0, nonmanifold_edges_ = 0;
  bool one_sided_ = false;
};

}  // namespace grains::contact
