#pragma once
// Pours of frictionless spheres or clumps into a box and their bulk solid
// fraction measured on a grid of sample points (a point counts once however
// many balls cover it, so the overlapping balls of a clump are not counted
// twice); shared by the CI (test_clump_packing.cpp) and long
// (test_clump_packing_long.cpp) clump regressions.
#include <gtest/gtest.h>

#include <chrono>
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

// ------------------------------------------------- periodic pours (resolution)

// Clumps of a mesh decomposition poured onto a floor in a box periodic in x
// and y (no side walls, so no wall ordering), and the bulk solid fraction
// between the floor and the free surface. Used by the resolution
// regressions (phi against n3): test_clump_packing.cpp (CI) and
// test_clump_packing_long.cpp (label long).
struct PeriodicPourConfig {
  std::string mesh = std::string(GRAINS_SOURCE_DIR) + "/cases/pour_clumps/cube.off";
  int grid = 8;
  double mu_decomposition = 0.25;
  double radius = 0.0008;    // bounding radius of a clump (m)
  int count = 250;
  double width = 0.006;      // periodic box side (m)
  double fill_top = 0.064;   // top of the random fill (m): bounding spheres at a solid fraction ~0.24
  double end = 0.18;         // s: fall from the top (0.114 s) and come to rest
  double youngs = 1.0e6, restitution = 0.5, friction = 0.5;
  double margin = 0.002;     // bulk region: this far above the floor and below the free surface (m)
  double spacing = 0.00003;  // sample grid spacing (m)
  int seed = 1;
};

struct PeriodicPour {
  double phi = 0;            // bulk solid fraction of the union of balls
  double bulk_lo = 0, bulk_hi = 0, surface = 0;  // m
  double speed = 0;          // largest body speed at the end (m/s)
  double rms_speed = 0;      // rms body speed at the end (m/s)
  double dt = 0, wall_s = 0;
  std::int64_t steps = 0;
  std::size_t bodies = 0, balls = 0;
};

// Fraction of the points of a grid of spacing h in [0, w)^2 x [zlo, zhi]
// covered by a ball, the balls taken with their periodic images in x and y.
inline double periodic_sampled_fraction(const std::vector<sim::Vec3>& x, const std::vector<double>& r, double w,
                                        double zlo, double zhi, double h) {
  const long nx = std::max<long>(1, std::lround(w / h)), nz = std::max<long>(1, std::lround((zhi - zlo) / h));
  const double hx = w / static_cast<double>(nx), hz = (zhi - zlo) / static_cast<double>(nz);
  std::vector<char> hit(static_cast<std::size_t>(nx * nx * nz), 0);
  auto mark = [&](const sim::Vec3& c, double rad) {
    const long k0 = std::max(0L, std::lround(std::ceil((c.z() - rad - zlo) / hz - 0.5)));
    const long k1 = std::min(nz - 1, std::lround(std::floor((c.z() + rad - zlo) / hz - 0.5)));
    if (k0 > k1) return;
    const long j0 = std::max(0L, std::lround(std::ceil((c.y() - rad) / hx - 0.5)));
    const long j1 = std::min(nx - 1, std::lround(std::floor((c.y() + rad) / hx - 0.5)));
    const long i0 = std::max(0L, std::lround(std::ceil((c.x() - rad) / hx - 0.5)));
    const long i1 = std::min(nx - 1, std::lround(std::floor((c.x() + rad) / hx - 0.5)));
    for (long k = k0; k <= k1; ++k) {
      const double dz = zlo + (static_cast<double>(k) + 0.5) * hz - c.z();
      for (long j = j0; j <= j1; ++j) {
        const double dy = (static_cast<double>(j) + 0.5) * hx - c.y();
        const double rest = rad * rad - dz * dz - dy * dy;
        if (rest <= 0) continue;
        char* row = &hit[static_cast<std::size_t>((k * nx + j) * nx)];
        for (long i = i0; i <= i1; ++i) {
          const double dx = (static_cast<double>(i) + 0.5) * hx - c.x();
          if (dx * dx < rest) row[i] = 1;
        }
      }
    }
  };
  for (std::size_t b = 0; b < x.size(); ++b) {
    sim::Vec3 c = x[b];
    c.x() -= w * std::floor(c.x() / w);
    c.y() -= w * std::floor(c.y() / w);
    for (int sx = -1; sx <= 1; ++sx)
      for (int sy = -1; sy <= 1; ++sy) {
        const sim::Vec3 q = c + sim::Vec3(sx * w, sy * w, 0);
        if (q.x() + r[b] < 0 || q.x() - r[b] > w || q.y() + r[b] < 0 || q.y() - r[b] > w) continue;
        mark(q, r[b]);
      }
  }
  long inside = 0;
  for (char c : hit) inside += c;
  return static_cast<double>(inside) / static_cast<double>(hit.size());
}

inline PeriodicPour pour_periodic(const PeriodicPourConfig& c) {
  std::ostringstream y;
  y.precision(17);
  const double w = c.width;
  y << "domain: {min: [0, 0, -0.001], max: [" << w << ", " << w << ", " << c.fill_top + 0.002
    << "], periodic: [true, true, false]}\ngravity: [0, 0, -9.81]\nmaterials:\n"
    << material("grain", 2500, c.youngs, 0.3, c.restitution, c.friction) << "particles:\n  - {name: g, material: grain, radius: "
    << c.radius << ", count: " << c.count << ", shape: {type: clump, mesh: " << c.mesh << ", grid: " << c.grid
    << ", mu: " << c.mu_decomposition << ", orientation: random}, placement: {type: random_fill, seed: " << c.seed
    << ", region: {min: [0, 0, 0], max: [" << w << ", " << w << ", " << c.fill_top << "]}}}\nwalls:\n"
    << "  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain}\n"
    << "time: {dt_rayleigh: 0.2, end: " << c.end << "}\n";
  auto s = from_yaml(y.str());
  const auto t0 = std::chrono::steady_clock::now();
  run_to_end(s);
  PeriodicPour r;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.dt = s.scene.clock.dt;
  r.steps = s.scene.clock.step;
  const auto& p = s.scene.particles;
  const auto& b = s.scene.bodies;
  r.balls = p.n_owned();
  r.bodies = b.size();
  double v2 = 0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    r.speed = std::max(r.speed, b.v[k].norm());
    v2 += b.v[k].squaredNorm();
  }
  r.rms_speed = b.size() ? std::sqrt(v2 / static_cast<double>(b.size())) : 0.0;
  std::vector<sim::Vec3> x(p.x.begin(), p.x.begin() + p.n_owned());
  std::vector<double> rad(p.radius.begin(), p.radius.begin() + p.n_owned());
  // Free surface: mean height of the highest 5 % of ball centres (postprocess::bulk_region's rule).
  std::vector<double> z;
  for (const auto& q : x) z.push_back(q.z());
  std::sort(z.begin(), z.end(), std::greater<>());
  const std::size_t top = std::max<std::size_t>(1, z.size() / 20);
  for (std::size_t i = 0; i < top; ++i) r.surface += z[i] / static_cast<double>(top);
  r.bulk_lo = c.margin;
  r.bulk_hi = r.surface - c.margin;
  EXPECT_GT(r.bulk_hi - r.bulk_lo, c.margin) << "bed too shallow for a bulk region";
  r.phi = periodic_sampled_fraction(x, rad, w, r.bulk_lo, std::max(r.bulk_hi, r.bulk_lo + c.spacing), c.spacing);
  std::cout << "periodic pour of " << c.count << " clumps (" << c.mesh.substr(c.mesh.find_last_of('/') + 1) << ", grid "
            << c.grid << ", " << r.balls / std::max<std::size_t>(1, r.bodies) << " balls each), seed " << c.seed
            << ": bulk phi = " << r.phi << " (z " << r.bulk_lo << "-" << r.bulk_hi << " m), largest body speed "
            << r.speed << " m/s, " << r.steps << " steps of " << r.dt << " s in " << r.wall_s << " s" << std::endl;
  return r;
}

}  // namespace grains::test
