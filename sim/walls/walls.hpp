#pragma once
// Walls: planes (infinite and one-sided, or finite: a disc or an annulus,
// e.g. a silo bottom with an orifice) and finite cylinder surfaces, each
// optionally moving with a prescribed constant velocity. A wall has a material (for the pair
// table) and, when the contact law keeps history, a slot in every particle's
// wall-history field.
#include <limits>
#include <string>
#include <vector>

#include "contact/cylinder.hpp"
#include "contact/plane.hpp"

namespace grains::sim {

using contact::Vec3;

struct PlaneWall {
  std::string name;
  Vec3 point{0, 0, 0};   // on the plane; the centre of the disc and of its hole when finite
  Vec3 normal{0, 0, 1};  // unit; particles are on this side (infinite planes)
  Vec3 velocity{0, 0, 0};
  int material = 0;
  int history_slot = 0;
  /// History slots from history_slot on: 2 for a finite plane in a scene with
  /// ellipsoids (a grain can touch an annulus at two places), else 1.
  int history_slots = 1;
  /// A hole of this radius about `point` (0: none) and an outer radius
  /// (infinite: none). With either, the wall is a zero-thickness annulus
  /// touched on both faces and on its rims (contact/plane.hpp).
  double hole_radius = 0;
  double radius = std::numeric_limits<double>::infinity();
  bool finite() const { return hole_radius > 0 || radius < std::numeric_limits<double>::infinity(); }
  contact::Annulus annulus() const { return {point, normal, hole_radius, radius}; }
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
