#pragma once
// The exact non-overlap check of insertion: the grains of the scene (and
// those inserted so far) in a hash grid, and the walls. A candidate grain
// fits when none of its parts overlaps a wall or another grain:
//   sphere-sphere: centre distance < r_1 + r_2 overlaps (touching is allowed);
//   anything with an ellipsoid: the Perram-Wertheim contact function
//   (contact/ellipsoid/pw85.hpp) mu^2 < 1 overlaps, a sphere being the
//   ellipsoid with form r^2 I;
//   walls: the contact geometry the force stages use (sphere_plane,
//   sphere_annulus, sphere_cylinder; ellipsoid_plane_contact,
//   ellipsoid_cylinder_contact).
// Along periodic axes the grains near a face are stored with their images,
// so queries need no wrapping.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "sim/insert/grain_geometry.hpp"
#include "sim/scene/scene.hpp"

namespace grains::sim::insert {

class Obstacles {
 public:
  /// `reach`: the largest sum of two bounding radii a query can meet (the
  /// largest grain part + the largest obstacle); the grid's cell size.
  Obstacles(const Domain& domain, const Walls& walls, double reach);
  void add_sphere(const Vec3& x, double r);
  void add_ellipsoid(const Vec3& x, const contact::SymMat3& form, double bound);
  void add(const GrainParts& g);
  /// True when g overlaps no wall and no stored grain.
  bool fits(const GrainParts& g) const;
  /// True when g overlaps no wall.
  bool clear_of_walls(const GrainParts& g) const;
  std::size_t size() const { return items_.size(); }

 private:
  struct Item {
    Vec3 x;
    double bound;  // sphere radius, or largest semi-axis
    bool ellipsoid;
    contact::SymMat3 form;
  };
  void store(const Item& it);
  void store_one(const Item& it);
  bool part_free(const Vec3& x, double bound, bool ell, const contact::SymMat3& form) const;
  long long key(const Vec3& x) const;
  Domain domain_;
  const Walls& walls_;
  double cell_;
  std::vector<Item> items_;
  std::unordered_map<long long, std::vector<std::uint32_t>> cells_;
};

}  // namespace grains::sim::insert
