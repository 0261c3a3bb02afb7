#include "sim/insert/obstacles.hpp"

#include <array>
#include <cmath>

#include "contact/ellipsoid/ellipsoid_walls.hpp"
#include "contact/ellipsoid/pw85.hpp"

namespace grains::sim::insert {

namespace {
contact::SymMat3 sphere_form(double r) { return {r * r, 0, 0, r * r, 0, r * r}; }
}  // namespace

Obstacles::Obstacles(const Domain& domain, const Walls& walls, double reach)
    : domain_(domain), walls_(walls), cell_(std::max(reach, 1e-300)) {}

long long Obstacles::key(const Vec3& x) const {
  auto c = [&](int d) { return static_cast<long long>(std::floor(x[d] / cell_)) & 0x1FFFFF; };
  return (c(0) << 42) | (c(1) << 21) | c(2);
}

void Obstacles::store_one(const Item& it) {
  cells_[key(it.x)].push_back(static_cast<std::uint32_t>(items_.size()));
  items_.push_back(it);
}

void Obstacles::store(const Item& it) {
  // The item and its images across the periodic faces it is near.
  std::array<std::array<double, 2>, 3> shifts{};
  std::array<int, 3> n{1, 1, 1};
  for (int d = 0; d < 3; ++d) {
    if (!domain_.periodic[d]) continue;
    const double L = domain_.hi[d] - domain_.lo[d];
    if (it.x[d] - domain_.lo[d] < cell_) shifts[d][n[d]++] = L;
    else if (domain_.hi[d] - it.x[d] < cell_) shifts[d][n[d]++] = -L;
  }
  for (int a = 0; a < n[0]; ++a)
    for (int b = 0; b < n[1]; ++b)
      for (int c = 0; c < n[2]; ++c) {
        Item im = it;
        im.x += Vec3(shifts[0][a], shifts[1][b], shifts[2][c]);
        store_one(im);
      }
}

void Obstacles::add_sphere(const Vec3& x, double r) { store({x, r, false, {}}); }

void Obstacles::add_ellipsoid(const Vec3& x, const contact::SymMat3& form, double bound) {
  store({x, bound, true, form});
}

void Obstacles::add(const GrainParts& g) {
  if (g.ellipsoid) add_ellipsoid(g.ell_centre, g.form, g.ell_bound);
  for (std::size_t k = 0; k < g.radii.size(); ++k) add_sphere(g.centres[k], g.radii[k]);
}

bool Obstacles::part_free(const Vec3& x, double bound, bool ell, const contact::SymMat3& form) const {
  const long long cx = static_cast<long long>(std::floor(x[0] / cell_)),
                  cy = static_cast<long long>(std::floor(x[1] / cell_)),
                  cz = static_cast<long long>(std::floor(x[2] / cell_));
  contact::Pw85Options opt;
  opt.stop_if_separated = true;
  for (long long dz = -1; dz <= 1; ++dz)
    for (long long dy = -1; dy <= 1; ++dy)
      for (long long dx = -1; dx <= 1; ++dx) {
        const long long k = (((cx + dx) & 0x1FFFFF) << 42) | (((cy + dy) & 0x1FFFFF) << 21) | ((cz + dz) & 0x1FFFFF);
        const auto it = cells_.find(k);
        if (it == cells_.end()) continue;
        for (const auto j : it->second) {
          const Item& o = items_[j];
          const Vec3 r = o.x - x;
          const double reach = bound + o.bound;
          const double d2 = r.squaredNorm();
          if (d2 >= reach * reach) continue;  // bounding spheres apart (or touching)
          if (!ell && !o.ellipsoid) return false;  // two spheres: the bounding test was exact
          const auto res = contact::pw85_contact(r, ell ? form : sphere_form(bound),
                                                 o.ellipsoid ? o.form : sphere_form(o.bound), opt);
          if (res.status == contact::Pw85Status::separated) continue;
          if (!(res.mu2 >= 1.0)) return false;  // overlapping (or not proven apart)
        }
      }
  return true;
}

bool Obstacles::clear_of_walls(const GrainParts& g) const {
  bool clear = true;
  if (g.ellipsoid) {
    contact::Ellipsoid e;
    e.centre = g.ell_centre;
    e.semi_axes = g.ell_axes;
    e.orientation = g.ell_orientation;
    walls_.for_each([&](const auto& w, std::size_t) { clear = clear && !w.touches(e); });
    return clear;
  }
  walls_.for_each([&](const auto& w, std::size_t) {
    for (std::size_t k = 0; clear && k < g.radii.size(); ++k) clear = !w.touches(g.centres[k], g.radii[k]);
  });
  return clear;
}

bool Obstacles::fits(const GrainParts& g) const {
  if (!clear_of_walls(g)) return false;
  if (g.ellipsoid) return part_free(g.ell_centre, g.ell_bound, true, g.form);
  for (std::size_t k = 0; k < g.radii.size(); ++k)
    if (!part_free(g.centres[k], g.radii[k], false, {})) return false;
  return true;
}

}  // namespace grains::sim::insert
