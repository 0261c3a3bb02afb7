#pragma once
// The plane wall kind: an infinite plane, one-sided (particles stay on the
// side its normal points to), or a finite plane: a zero-thickness annulus
// about `point` (a disc, or a plane with a circular hole such as a silo
// bottom with its orifice), touched on both faces and on its rims. An
// ellipsoid can touch an annulus at two places at once (lying across the
// hole): two history slots per particle then (contact/ellipsoid/ellipsoid_walls.hpp).
// Registered in wall_kinds.hpp; the interface is described in wall_kind.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "contact/ellipsoid/ellipsoid_walls.hpp"
#include "contact/plane.hpp"
#include "sim/keys/effect_doc.hpp"
#include "sim/state/particle_store.hpp"
#include "sim/walls/wall_kind.hpp"

namespace grains::sim {

struct PlaneWall : WallCommon {
  static constexpr const char* kind = "plane";
  static constexpr const char* position_name = "point";
  static constexpr bool controllable = true;  // walls[].control (wall_control.hpp)

  Vec3 point{0, 0, 0};   // on the plane; the centre of the disc and of its hole when finite
  Vec3 normal{0, 0, 1};  // unit; particles are on this side (infinite planes)
  /// A hole of this radius about `point` (0: none) and an outer radius
  /// (infinite: none). With either, the wall is a zero-thickness annulus
  /// touched on both faces and on its rims (contact/plane.hpp).
  double hole_radius = 0;
  double radius = std::numeric_limits<double>::infinity();
  bool finite() const { return hole_radius > 0 || radius < std::numeric_limits<double>::infinity(); }
  contact::Annulus annulus() const { return {point, normal, hole_radius, radius}; }

  static std::string summary() {
    return "An infinite plane; particles stay on the side its normal points to. Contacts use the same law as "
           "particle pairs with the wall as an infinitely heavy body. With hole_radius and/or radius the plane is "
           "finite: a zero-thickness annulus (a disc, or a plane with a circular hole such as a silo bottom with its "
           "orifice) about `point`, touched on both faces and on its rims; particles pass through the hole. An "
           "ellipsoid can touch it at two places at once (e.g. lying across the hole).";
  }
  static std::vector<KeySpec> keys() {
    const double inf = std::numeric_limits<double>::infinity();
    using K = KeyType;
    return {key("point", K::Vec3, "a point on the plane; the centre of the hole and of the disc").req().si("m"),
            key("normal", K::Vec3, "normal towards the particles (normalised for you)").req(),
            key("hole_radius", K::Number, "radius of a circular hole about point (an orifice)")
                .def(0.0)
                .si("m")
                .in(0, inf),
            key("radius", K::Number, "outer radius of a finite disc (> hole_radius)")
                .def("infinite")
                .si("m")
                .in(0, inf, true)};
  }
  static PlaneWall from_keys(KeyReader& r) {
    PlaneWall p;
    p.point = r.vec3("point", Vec3::Zero());
    p.normal = r.direction("normal", Vec3(0, 0, 1));
    p.hole_radius = r.number("hole_radius", 0);
    p.radius = r.number("radius", std::numeric_limits<double>::infinity());
    if (r.has("radius") && p.radius <= p.hole_radius)
      r.error("radius", "radius must be larger than hole_radius (" + std::to_string(p.hole_radius) + " m)");
    return p;
  }

  int slots(bool ellipsoids) const { return ellipsoids && finite() ? 2 : 1; }

  /// The particles [0, n) within their radius + skin of the plane (or annulus).
  void near_list(const ParticleStore& p, std::size_t n, double skin, bool /*shapes*/,
                 std::vector<std::uint32_t>& out, NearItems&) const {
    if (finite()) {  // touched from both sides and on its rims
      const auto a = annulus();
      for (std::size_t i = 0; i < n; ++i) {
        const double reach = p.radius[i] + skin;
        if ((p.x[i] - contact::annulus_nearest(p.x[i], a)).squaredNorm() < reach * reach)
          out.push_back(static_cast<std::uint32_t>(i));
      }
      return;
    }
    const Vec3 q = point, m = normal;
    for (std::size_t i = 0; i < n; ++i)
      if (contact::plane_distance(p.x[i], q, m) < p.radius[i] + skin) out.push_back(static_cast<std::uint32_t>(i));
  }

  template <bool Shapes, class Slots, class Emit>
  GRAINS_INLINE void contacts(const ParticleStore& p, std::size_t i, std::span<const std::uint32_t>, Slots&& slots,
                              Emit&& emit) const {
    contact::ContactGeometry g;
    if (!finite()) {
      if constexpr (Shapes) {
        if (p.shape[i] == kEllipsoid) {
          bool touching;
          g = contact::ellipsoid_plane_contact(p.x[i], p.form[i], p.semi_axes[i], contact::Plane{point, normal},
                                               &touching);
          if (touching) emit(g, 0);
          return;
        }
      }
      if (contact::sphere_plane(p.x[i], slots.grown(p.radius[i]), point, normal, g)) emit(g, 0);
      return;
    }
    if constexpr (Shapes) {
      if (p.shape[i] == kEllipsoid) {
        ellipsoid_annulus(p, i, slots, emit);
        return;
      }
    }
    if (contact::sphere_annulus(p.x[i], slots.grown(p.radius[i]), annulus(), g)) emit(g, 0);
  }

  bool touches(const Vec3& x, double r) const {
    contact::ContactGeometry g;
    return finite() ? contact::sphere_annulus(x, r, annulus(), g) : contact::sphere_plane(x, r, point, normal, g);
  }
  bool touches(const contact::Ellipsoid& e) const {
    if (finite()) return contact::ellipsoid_annulus_contacts(e, annulus()).count > 0;
    bool touching = false;
    contact::ellipsoid_plane_contact(e, contact::Plane{point, normal}, &touching);
    return touching;
  }

  void translate(const Vec3& d) { point += d; }
  Vec3& position() { return point; }
  const Vec3& position() const { return point; }

  /// An infinite plane: a square centred at the projection of the domain's
  /// centre, as wide as the domain's diagonal. A finite one: a ring of 64
  /// quads between the hole and the outer rim (an unbounded annulus out to
  /// the half diagonal beyond the hole's centre).
  void cells(WallSurface& s, const Vec3& centre, double half) const {
    const Vec3 a = normal.unitOrthogonal();
    const Vec3 b = normal.cross(a);
    const int first = static_cast<int>(s.points.size());
    if (finite()) {
      const double r_out = std::isfinite(radius) ? radius : (point - centre).norm() + half;
      const int seg = 64;
      for (int k = 0; k < seg; ++k) {
        const double t = 2 * M_PI * k / seg;
        const Vec3 e = std::cos(t) * a + std::sin(t) * b;
        s.points.push_back(point + hole_radius * e);
        s.points.push_back(point + r_out * e);
      }
      for (int k = 0; k < seg; ++k) {
        const int k2 = (k + 1) % seg;
        s.quads.push_back({first + 2 * k, first + 2 * k2, first + 2 * k2 + 1, first + 2 * k + 1});
      }
      return;
    }
    const Vec3 o = centre - normal * normal.dot(centre - point);
    const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
    for (int k = 0; k < 4; ++k) s.points.push_back(o + half * (sx[k] * a + sy[k] * b));
    s.quads.push_back({first, first + 1, first + 2, first + 3});
  }

  /// point, normal, hole radius, outer radius (-1: infinite).
  std::vector<double> record() const {
    return {point.x(), point.y(), point.z(), normal.x(), normal.y(), normal.z(), hole_radius,
            std::isfinite(radius) ? radius : -1.0};
  }
  static bool from_record(const std::vector<double>& v, PlaneWall& w) {
    if (v.size() != 8) return false;
    w.point = Vec3(v[0], v[1], v[2]);
    w.normal = Vec3(v[3], v[4], v[5]);
    w.hole_radius = v[6];
    w.radius = v[7] < 0 ? std::numeric_limits<double>::infinity() : v[7];
    return w.normal.norm() > 0;
  }

 private:
  // Up to two contacts (contact/ellipsoid/ellipsoid_walls.hpp), each in its
  // own slot. A lone contact (face or rim), or a face contact beside a rim
  // one, continues the slot that holds history if only one does: it is the
  // contact of the previous step, moved (e.g. from the rim onto the face).
  template <class Slots, class Emit>
  GRAINS_INLINE void ellipsoid_annulus(const ParticleStore& p, std::size_t i, Slots& slots, Emit&& emit) const {
    const contact::AnnulusContacts a =
        contact::ellipsoid_annulus_contacts({p.x[i], p.semi_axes[i], p.orientation[i]}, annulus());
    int slot[2] = {a.slot[0], a.slot[1]};
    if (a.count == 1 || a.face[0]) {
      const bool h0 = slots.held(0), h1 = slots.held(1);
      if (h0 != h1) {
        slot[0] = h0 ? 0 : 1;
        slot[1] = 1 - slot[0];
      }
    }
    for (int k = 0; k < a.count; ++k) emit(a.g[k], slot[k]);
  }
};

}  // namespace grains::sim
