#include "postprocess/packing_fraction.hpp"

#include <algorithm>
#include <cmath>

namespace grains::postprocess {

namespace {

// Antiderivative of sqrt(r^2 - x^2).
double S(double x, double r) {
  x = std::clamp(x, -r, r);
  return 0.5 * (x * std::sqrt(std::max(0.0, r * r - x * x)) + r * r * std::asin(x / r));
}

// Area of the disk of radius r at the origin with x <= a and y <= b.
double quadrant(double a, double b, double r) {
  if (a <= -r || b <= -r) return 0.0;
  const double hi = std::min(a, r);
  // Over x in [-r, hi]: the vertical chord [-h, h] clipped to y <= b.
  if (b >= r) return 2 * (S(hi, r) - S(-r, r));
  const double c = std::sqrt(r * r - b * b);  // |x| >= c: h <= |b|
  double area = 0;
  auto part = [&](double lo, double up, double ch, double cb) {
    lo = std::max(lo, -r);
    up = std::min(up, hi);
    if (up <= lo) return;
    area += ch * (S(up, r) - S(lo, r)) + cb * b * (up - lo);
  };
  if (b >= 0) {
    part(-r, -c, 2, 0);  // whole chord below b
    part(-c, c, 1, 1);   // chord from -h to b
    part(c, r, 2, 0);
  } else {
    part(-c, c, 1, 1);  // only where h > -b
  }
  return area;
}

// 16-point Gauss-Legendre on [-1, 1].
constexpr double kGx[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                           0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
constexpr double kGw[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                           0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};

}  // namespace

double disk_rectangle_area(double cx, double cy, double r, double x0, double x1, double y0, double y1) {
  if (r <= 0 || x1 <= x0 || y1 <= y0) return 0.0;
  const double a0 = x0 - cx, a1 = x1 - cx, b0 = y0 - cy, b1 = y1 - cy;
  return std::max(0.0, quadrant(a1, b1, r) - quadrant(a0, b1, r) - quadrant(a1, b0, r) + quadrant(a0, b0, r));
}

double sphere_box_volume(const Vec3& c, double r, const Box& b) {
  const double z0 = std::max(b.lo.z(), c.z() - r), z1 = std::min(b.hi.z(), c.z() + r);
  if (z1 <= z0) return 0.0;
  if ((c.array() - r >= b.lo.array()).all() && (c.array() + r <= b.hi.array()).all()) return 4.0 / 3.0 * M_PI * r * r * r;
  // Split the z-range where the slice's disk radius meets an edge or corner
  // distance: between the splits the slice area is smooth.
  std::vector<double> cuts{z0, z1};
  const double dx[2] = {b.lo.x() - c.x(), b.hi.x() - c.x()}, dy[2] = {b.lo.y() - c.y(), b.hi.y() - c.y()};
  std::vector<double> d;
  for (double u : dx) d.push_back(std::abs(u));
  for (double v : dy) d.push_back(std::abs(v));
  for (double u : dx)
    for (double v : dy) d.push_back(std::hypot(u, v));
  for (double q : d)
    if (q < r) {
      const double h = std::sqrt(r * r - q * q);
      for (double z : {c.z() - h, c.z() + h})
        if (z > z0 && z < z1) cuts.push_back(z);
    }
  std::sort(cuts.begin(), cuts.end());
  double vol = 0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double m = 0.5 * (cuts[k] + cuts[k + 1]), h = 0.5 * (cuts[k + 1] - cuts[k]);
    if (h <= 0) continue;
    // Substitution z = m + h sin(pi/2 t) clusters nodes at the ends, where
    // the slice radius has a square-root behaviour at the poles.
    for (int i = 0; i < 8; ++i)
      for (int s : {-1, 1}) {
        const double t = s * kGx[i];
        const double z = m + h * std::sin(0.5 * M_PI * t);
        const double jac = h * 0.5 * M_PI * std::cos(0.5 * M_PI * t);
        const double rho2 = r * r - (z - c.z()) * (z - c.z());
        if (rho2 <= 0) continue;
        vol += kGw[i] * jac *
               disk_rectangle_area(c.x(), c.y(), std::sqrt(rho2), b.lo.x(), b.hi.x(), b.lo.y(), b.hi.y());
      }
  }
  return vol;
}

double packing_fraction(const std::vector<Vec3>& x, const std::vector<double>& r, const Box& b) {
  double v = 0;
  for (std::size_t i = 0; i < x.size(); ++i) v += sphere_box_volume(x[i], r[i], b);
  return v / b.volume();
}

Box bulk_region(const std::vector<Vec3>& x, const std::vector<double>& r, const Box& container, double margin) {
  // Free surface: mean height of the highest 5% of centres (at least one).
  std::vector<double> z;
  z.reserve(x.size());
  for (const auto& p : x) z.push_back(p.z());
  std::sort(z.begin(), z.end(), std::greater<>());
  const std::size_t k = std::max<std::size_t>(1, z.size() / 20);
  double top = 0;
  for (std::size_t i = 0; i < k; ++i) top += z[i];
  top /= static_cast<double>(k);
  double rmax = 0;
  for (double q : r) rmax = std::max(rmax, q);
  Box b;
  b.lo = container.lo + Vec3::Constant(margin);
  b.hi = Vec3(container.hi.x() - margin, container.hi.y() - margin, top - margin);
  return b;
}

}  // namespace grains::postprocess
