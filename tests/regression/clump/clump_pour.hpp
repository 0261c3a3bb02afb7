#pragma once
// Pours of frictionless spheres or clumps into a box and their bulk solid
// fraction measured on a grid of sample points (a point counts once however
// many balls cover it, so the overlapping balls of a clump are not counted
// twice); shared by the CI (test_clump_packing.cpp) and long
// (test_clump_packing_long.cpp) clump regressions.
#include <gtest/gtest.h>

#include <unordered_map>

#include "postprocess/packing_fraction.hpp"
#include "tests/physics/clump/clump_cases.hpp"
#include "tests/regression/packing_support.hpp"

namespace grains::test {

// Fraction of a grid of points (spacing h) in the box covered by some ball.
inline double sampled_fraction(const sim::ParticleStore& p, const postprocess::Box& box, double h) {
  double rmax = 0;
  for (std::size_t i = 0; i < p.n_owned(); ++i) rmax = std::max(rmax, p.radius[i]);
  const double cell = 2 * rmax;
  auto key = [&](long x, long y, long z) { return (x * 73856093L) ^ (y * 19349663L) ^ (z * 83492791L); };
  std::unordered_map<long, std::vector<std::size_t>> grid;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    grid[key(std::lround(std::floor(p.x[i].x() / cell)), std::lround(std::floor(p.x[i].y() / cell)),
             std::lround(std::floor(p.x[i].z() / cell)))]
        .push_back(i);
  long inside = 0, total = 0;
  for (double z = box.lo.z() + h / 2; z < box.hi.z(); z += h)
    for (double y = box.lo.y() + h / 2; y < box.hi.y(); y += h)
      for (double x = box.lo.x() + h / 2; x < box.hi.x(); x += h) {
        ++total;
        const sim::Vec3 q(x, y, z);
        const long cx = std::lround(std::floor(x / cell)), cy = std::lround(std::floor(y / cell)),
                   cz = std::lround(std::floor(z / cell));
        bool hit = false;
        for (long dz = -1; dz <= 1 && !hit; ++dz)
          for (long dy = -1; dy <= 1 && !hit; ++dy)
            for (long dx = -1; dx <= 1 && !hit; ++dx) {
              auto it = grid.find(key(cx + dx, cy + dy, cz + dz));
              if (it == grid.end()) continue;
              for (auto i : it->second)
                if ((p.x[i] - q).squaredNorm() < p.radius[i] * p.radius[i]) {
                  hit = true;
                  break;
                }
            }
        inside += hit;
      }
  return static_cast<double>(inside) / static_cast<double>(total);
}

struct ClumpPour {
  double phi = 0, phi_exact_spheres = -1, speed = 0;
  std::size_t bodies = 0, balls = 0;
};

// Pours `count` grains of `shape` (radius = bounding radius) into a w x w box,
// frictionless, e = 0.1, and measures phi in the bulk (margin 2 volume-equivalent diameters).
inline ClumpPour pour(const std::string& shape, double radius, double d_eq, int count, double w, double end, int seed = 3) {
  std::ostringstream y;
  y.precision(17);
  const double top = 12 * w;
  y << "domain: {min: [-0.001, -0.001, -0.001], max: [" << w + 0.001 << ", " << w + 0.001 << ", " << top + 0.001
    << "]}\ngravity: [0, 0, -9.81]\nmaterials:\n"
    << material("grain", 2500, 1e7, 0.3, 0.1, 0.0) << "particles:\n  - {name: g, material: grain, radius: " << radius
    << ", count: " << count << ", shape: " << shape
    << ", placement: {type: random_fill, seed: " << seed << ", region: {min: [0, 0, 0], max: [" << w << ", " << w << ", " << top
    << "]}}}\nwalls:\n"
    << "  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain}\n"
    << "  - {type: plane, name: x0, point: [0, 0, 0], normal: [1, 0, 0], material: grain}\n"
    << "  - {type: plane, name: x1, point: [" << w << ", 0, 0], normal: [-1, 0, 0], material: grain}\n"
    << "  - {type: plane, name: y0, point: [0, 0, 0], normal: [0, 1, 0], material: grain}\n"
    << "  - {type: plane, name: y1, point: [0, " << w << ", 0], normal: [0, -1, 0], material: grain}\n"
    << "time: {dt_rayleigh: 0.25, end: " << end << "}\n";
  auto s = from_yaml(y.str());
  run_to_end(s);
  const auto& p = s.scene.particles;
  ClumpPour r;
  r.balls = p.n_owned();
  r.bodies = s.scene.bodies.size();
  for (std::size_t i = 0; i < p.n_owned(); ++i) r.speed = std::max(r.speed, p.v[i].norm());
  std::vector<postprocess::Vec3> x(p.x.begin(), p.x.begin() + p.n_owned());
  std::vector<double> rad(p.radius.begin(), p.radius.begin() + p.n_owned());
  const postprocess::Box container{postprocess::Vec3(0, 0, 0), postprocess::Vec3(w, w, 1)};
  const auto bulk = postprocess::bulk_region(x, rad, container, 2 * d_eq);
  EXPECT_GT(bulk.hi.z() - bulk.lo.z(), 3 * d_eq) << "bed too shallow for a bulk region";
  r.phi = sampled_fraction(p, bulk, d_eq / 25);
  if (r.bodies == 0) r.phi_exact_spheres = postprocess::packing_fraction(x, rad, bulk);
  return r;
}

}  // namespace grains::test
