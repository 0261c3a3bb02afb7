#pragma once
// Walls: infinite planes and finite cylinder surfaces, each optionally moving
// with a prescribed constant velocity. A wall has a material (for the pair
// table) and, when the contact law keeps history, a slot in every particle's
// wall-history field.
#include <string>
#include <vector>

#include "contact/cylinder.hpp"
#include "contact/plane.hpp"

namespace grains::sim {

using contact::Vec3;

struct PlaneWall {
  std::string name;
  Vec3 point{0, 0, 0};
  Vec3 normal{0, 0, 1};  // unit; particles are on this side
  Vec3 velocity{0, 0, 0};
  int material = 0;
  int history_slot = 0;
};

struct CylinderWall {
  std::string name;
  contact::CylinderSurface surface{};
  Vec3 velocity{0, 0, 0};
  int material = 0;
  int history_slot = 0;
};

struct Walls {
  std::vector<PlaneWall> planes;
  std::vector<CylinderWall> cylinders;
  std::size_t count() const { return planes.size() + cylinders.size(); }
  /// Largest distance any wall has moved in time t.
  double max_displacement(double t) const;
  void advance(double dt);
};

}  // namespace grains::sim
