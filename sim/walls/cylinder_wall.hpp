#pragma once
// The cylinder wall kind: the lateral surface of a finite circular cylinder
// (end caps are separate planes), holding particles inside (a silo) or
// keeping them outside (a post). Registered in wall_kinds.hpp; the interface
// is described in wall_kind.hpp.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "contact/cylinder.hpp"
#include "contact/ellipsoid/ellipsoid_walls.hpp"
#include "sim/keys/effect_doc.hpp"
#include "sim/state/particle_store.hpp"
#include "sim/walls/wall_kind.hpp"

namespace grains::sim {

struct CylinderWall : WallCommon {
  static constexpr const char* kind = "cylinder";
  static constexpr const char* position_name = "base";
  static constexpr bool controllable = false;  // walls[].control (wall_control.hpp)

  contact::CylinderSurface surface{Vec3(0, 0, 0), Vec3(0, 0, 1), 1, 0, 1, true};

  static std::string summary() { return "The lateral surface of a finite circular cylinder (add planes for end caps)."; }
  static std::vector<KeySpec> keys() {
    const double inf = std::numeric_limits<double>::infinity();
    using K = KeyType;
    return {key("base", K::Vec3, "centre of the bottom end of the axis").req().si("m"),
            key("axis", K::Vec3, "axis direction (normalised for you)").def("[0, 0, 1]"),
            key("radius", K::Number, "radius of the surface").req().si("m").in(0, inf, true),
            key("height", K::Number, "length along the axis from base").req().si("m").in(0, inf, true),
            key("inside", K::Bool, "true: particles are held inside (a silo); false: kept outside (a post)")
                .def_bool(true)};
  }
  static CylinderWall from_keys(KeyReader& r) {
    CylinderWall c;
    c.surface.base = r.vec3("base", Vec3::Zero());
    c.surface.axis = r.direction("axis", Vec3(0, 0, 1));
    c.surface.radius = r.number("radius", 1);
    c.surface.t_min = 0;
    c.surface.t_max = r.number("height", 1);
    c.surface.inside = r.boolean("inside", true);
    return c;
  }

  int slots(bool) const { return 1; }

  /// The surface widened by the skin; a non-spherical particle (radius = its
  /// bounding sphere) may touch it at a point up to its radius along the axis
  /// from its centre.
  void near_list(const ParticleStore& p, std::size_t n, double skin, bool shapes, std::vector<std::uint32_t>& out,
                 NearItems&) const {
    auto s = surface;
    s.t_min -= skin;
    s.t_max += skin;
    s.radius += s.inside ? -skin : skin;
    contact::ContactGeometry g;
    for (std::size_t i = 0; i < n; ++i) {
      auto si = s;
      if (shapes) {
        si.t_min -= p.radius[i];
        si.t_max += p.radius[i];
      }
      if (contact::sphere_cylinder(p.x[i], p.radius[i], si, g)) out.push_back(static_cast<std::uint32_t>(i));
    }
  }

  template <bool Shapes, class Slots, class Emit>
  GRAINS_INLINE void contacts(const ParticleStore& p, std::size_t i, std::span<const std::uint32_t>, Slots&& slots,
                              Emit&& emit) const {
    contact::ContactGeometry g;
    if constexpr (Shapes) {
      if (p.shape[i] == kEllipsoid) {
        bool touching;
        g = contact::ellipsoid_cylinder_contact({p.x[i], p.semi_axes[i], p.orientation[i]}, surface, &touching);
        if (touching) emit(g, 0);
        return;
      }
    }
    if (contact::sphere_cylinder(p.x[i], slots.grown(p.radius[i]), surface, g)) emit(g, 0);
  }

  bool touches(const Vec3& x, double r) const {
    contact::ContactGeometry g;
    return contact::sphere_cylinder(x, r, surface, g);
  }
  bool touches(const contact::Ellipsoid& e) const {
    bool touching = false;
    contact::ellipsoid_cylinder_contact(e, surface, &touching);
    return touching;
  }

  void translate(const Vec3& d) { surface.base += d; }
  Vec3& position() { return surface.base; }
  const Vec3& position() const { return surface.base; }

  /// A ring of 64 quads between the bottom and top circles.
  void cells(WallSurface& s, const Vec3&, double) const {
    const auto& sf = surface;
    const Vec3 a = sf.axis.unitOrthogonal();
    const Vec3 b = sf.axis.cross(a);
    const int seg = 64;
    const int first = static_cast<int>(s.points.size());
    for (int k = 0; k < seg; ++k) {
      const double t = 2 * M_PI * k / seg;
      const Vec3 rr = sf.radius * (std::cos(t) * a + std::sin(t) * b);
      s.points.push_back(sf.base + sf.axis * sf.t_min + rr);
      s.points.push_back(sf.base + sf.axis * sf.t_max + rr);
    }
    for (int k = 0; k < seg; ++k) {
      const int k2 = (k + 1) % seg;
      s.quads.push_back({first + 2 * k, first + 2 * k2, first + 2 * k2 + 1, first + 2 * k + 1});
    }
  }

  /// base, axis, radius, t_min, t_max, inside (1/0).
  std::vector<double> record() const {
    const auto& c = surface;
    return {c.base.x(), c.base.y(), c.base.z(), c.axis.x(), c.axis.y(), c.axis.z(), c.radius, c.t_min, c.t_max,
            c.inside ? 1.0 : 0.0};
  }
  static bool from_record(const std::vector<double>& v, CylinderWall& w) {
    if (v.size() != 10) return false;
    w.surface = {Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5]), v[6], v[7], v[8], v[9] != 0};
    return w.surface.axis.norm() > 0 && w.surface.radius > 0;
  }
};

}  // namespace grains::sim
