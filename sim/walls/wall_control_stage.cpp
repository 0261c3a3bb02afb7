#include "sim/walls/wall_control_stage.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "sim/parallel/exchange.hpp"
#include "sim/scene/scene_config.hpp"

namespace grains::sim {

namespace {

// The axis d lies along (0, 1, 2), or -1 when it is not along one.
int axis_of(const Vec3& d) {
  for (int a = 0; a < 3; ++a)
    if (std::abs(d[a]) > 1 - 1e-12) return a;
  return -1;
}

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

// The gap between the infinite planes facing each other across axis b (0: none).
double plane_gap(const Scene& s, int b) {
  double lo, hi;
  return s.walls.facing_planes(b, lo, hi) ? hi - lo : 0.0;
}

}  // namespace

double box_cross_section(const Scene& s, const Vec3& d, std::string* why) {
  for (const auto& c : s.walls.of<CylinderWall>())
    if (c.surface.inside && std::abs(c.surface.axis.dot(d)) > 1 - 1e-12)
      return M_PI * c.surface.radius * c.surface.radius;
  const int a = axis_of(d);
  if (a < 0) {
    if (why) *why = "its direction is not along x, y or z, so the box's cross-section is not defined; give area";
    return 0;
  }
  double area = 1;
  for (int b = 0; b < 3; ++b) {
    if (b == a) continue;
    const double L = s.domain.periodic[b] ? s.domain.hi[b] - s.domain.lo[b] : plane_gap(s, b);
    if (!(L > 0)) {
      if (why)
        *why = std::string("no cross-section: along ") + axis_name(b) +
               " the domain is not periodic and no two infinite planes face each other; give area";
      return 0;
    }
    area *= L;
  }
  return area;
}

double box_length(const Scene& s, const Vec3& point, const Vec3& d, std::string* why) {
  double L = std::numeric_limits<double>::infinity();
  for (const auto& p : s.walls.of<PlaneWall>()) {
    if (p.finite() || p.normal.dot(d) > -1 + 1e-12) continue;
    const double gap = (p.point - point).dot(d);
    if (gap > 0) L = std::min(L, gap);
  }
  if (std::isfinite(L)) return L;
  if (why) *why = "a strain rate needs the sample's length: no infinite plane faces this one (normal opposite)";
  return 0;
}

void setup_wall_controls(Scene& s, bool arkode, const std::string& integrator_where) {
  if (!s.walls.controlled()) return;
  s.walls.for_each([&](auto& w, std::size_t) {
    WallControl& c = w.control;
    if (!c.active()) return;
    const std::string at = c.where + ": walls '" + w.name + "' control: ";
    if (arkode)
      throw SetupError(at + "a controlled wall moves by the Verlet step; use time.integrator: verlet (" +
                       integrator_where + ")");
    std::string why;
    if (c.mode == WallControl::Mode::Stress && c.area == 0 && box_cross_section(s, c.direction, &why) == 0)
      throw SetupError(at + why);
    if constexpr (requires { w.normal; }) {
      if (c.mode == WallControl::Mode::StrainRate) {
        const double L = box_length(s, w.point, c.direction, &why);
        if (L == 0) throw SetupError(at + why);
        c.speed = c.target * L;  // from the first step on
        c.max_speed = std::abs(c.speed);
        w.velocity = c.speed * c.direction;
      }
    }
  });
  s.wall_loads.assign(s.walls.count(), {});  // the wall stage sums them from now on
}

void ControlWalls::run(Scene& s) {
  // The loads of the controlled walls, summed over the ranks (each summed its own grains).
  std::vector<double>& v = sums_;
  v.clear();
  s.walls.for_each([&](const auto& w, std::size_t k) {
    if (!w.control.active()) return;
    const WallLoad& l = s.wall_loads[k];
    v.push_back(-l.force.dot(w.control.direction));
    v.push_back(l.stiffness);
    v.push_back(l.damping);
  });
  if (s.exchange) s.exchange->comm().sum_in_place(v);
  std::size_t m = 0;
  const double dt = s.clock.dt;
  s.walls.for_each([&](auto& w, std::size_t) {
    WallControl& c = w.control;
    if (!c.active()) return;
    c.load = v[m++];
    c.stiffness = v[m++];
    c.damping = v[m++];
    // The stress's area (a strain-controlled wall's too, when the box has one: its stress is output).
    c.area_now = c.area > 0 ? c.area : c.mode == WallControl::Mode::Force ? 0.0 : box_cross_section(s, c.direction, nullptr);
    if (c.servo()) {
      c.target_load = c.mode == WallControl::Mode::Force ? c.target : c.target * c.area_now;
      c.speed = c.servo_speed(c.load, c.target_load, c.stiffness, c.damping, dt);
    } else if constexpr (requires { w.normal; }) {  // strain rate (planes)
      c.speed = c.target * box_length(s, w.point, c.direction, nullptr);
      c.max_speed = std::max(c.max_speed, std::abs(c.speed));
    }
    if constexpr (!requires { w.motion_time; }) w.velocity = c.speed * c.direction;
  });
}

}  // namespace grains::sim
