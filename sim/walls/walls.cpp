#include "sim/walls/walls.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace grains::sim {

double Walls::max_displacement(double t) const {
  double m = 0;
  for_each([&](const auto& w, std::size_t) {
    if constexpr (requires { w.max_displacement(t); })
      m = std::max(m, w.max_displacement(t) + w.control.max_speed * t);  // a kind that knows its motion's history
    else if (w.control.active())  // its speed changes, within its bound
      m = std::max(m, w.control.max_speed * t);
    else
      m = std::max(m, w.max_speed() * t);
  });
  return m;
}

bool Walls::facing_planes(int d, double& lo, double& hi) const {
  lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (const auto& p : of<PlaneWall>()) {
    if (p.finite()) continue;
    if (p.normal[d] > 1 - 1e-12) lo = std::max(lo, p.point[d]);
    if (p.normal[d] < -1 + 1e-12) hi = std::min(hi, p.point[d]);
  }
  return std::isfinite(lo) && std::isfinite(hi);
}

double Walls::max_speed() const {
  double m = 0;
  for_each([&](const auto& w, std::size_t) {
    m = std::max(m, w.control.active() ? w.max_speed() + w.control.max_speed : w.max_speed());
  });
  return m;
}

std::string Walls::describe() const {
  std::string out;
  for_each_type(WallKinds{}, [&]<class K>() {
    out += (out.empty() ? "" : ", ") + std::to_string(of<K>().size()) + " " + K::kind + "(s)";
  });
  return out;
}

void Walls::advance(double dt) {
  for_each([&](auto& w, std::size_t) {
    if (w.control.active()) w.control.travel += w.control.speed * dt;  // (a plane's velocity is its speed)
    if constexpr (requires { w.advance(dt); })
      w.advance(dt);
    else
      w.translate(w.velocity * dt);
  });
}

}  // namespace grains::sim
