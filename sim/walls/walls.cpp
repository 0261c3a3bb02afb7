#include "sim/walls/walls.hpp"

#include <algorithm>

namespace grains::sim {

double Walls::max_displacement(double t) const {
  double m = 0;
  for (const auto& w : planes) m = std::max(m, w.velocity.norm() * t);
  for (const auto& w : cylinders) m = std::max(m, w.velocity.norm() * t);
  return m;
}

void Walls::advance(double dt) {
  for (auto& w : planes) w.point += w.velocity * dt;
  for (auto& w : cylinders) w.surface.base += w.velocity * dt;
}

}  // namespace grains::sim
