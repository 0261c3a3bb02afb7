#include "sim/insert/grain_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace grains::sim::insert {

GrainParts grain_parts(const ShapeConfig& shape, double q, const Vec3& x, const Quat& o) {
  GrainParts g;
  switch (shape.kind) {
    case ShapeConfig::Kind::Sphere:
      g.centres.push_back(x);
      g.radii.push_back(q);
      break;
    case ShapeConfig::Kind::Clump: {
      const Eigen::Matrix3d R = o.toRotationMatrix();
      const auto& c = *shape.clump;
      for (std::size_t k = 0; k < c.radii.size(); ++k) {
        g.centres.push_back(x + R * (q * c.centres[k]));
        g.radii.push_back(q * c.radii[k]);
      }
      break;
    }
    case ShapeConfig::Kind::Ellipsoid: {
      const Vec3 axes = q * shape.axes_rel;
      g.ellipsoid = true;
      g.ell_centre = x;
      g.form = contact::quadratic_form(axes, o);
      g.ell_bound = axes.maxCoeff();
      g.ell_axes = axes;
      g.ell_orientation = o;
      break;
    }
  }
  return g;
}

void ellipsoid_cover(const Vec3& axes, std::vector<Vec3>& centres, std::vector<double>& radii) {
  int ax = 0;
  axes.maxCoeff(&ax);
  const double a = axes[ax];
  const double b = std::max(axes[(ax + 1) % 3], axes[(ax + 2) % 3]);
  const int n = std::max(1, static_cast<int>(std::ceil(1.5 * a / b - 1e-9)));
  const double w = 2 * a / n;
  auto reach2 = [&](double xk, double x) { return (x - xk) * (x - xk) + b * b * std::max(0.0, 1 - x * x / (a * a)); };
  for (int k = 0; k < n; ++k) {
    const double x0 = -a + k * w, x1 = x0 + w, xk = 0.5 * (x0 + x1);
    Vec3 c = Vec3::Zero();
    c[ax] = xk;
    centres.push_back(c);  // reaches the farthest end of its slab (convexity, see header)
    radii.push_back(std::sqrt(std::max(reach2(xk, x0), reach2(xk, x1))) * (1 + 1e-12));
  }
}

void cover_balls(const ShapeConfig& shape, double q, std::vector<Vec3>& centres, std::vector<double>& radii) {
  switch (shape.kind) {
    case ShapeConfig::Kind::Sphere:
      centres.push_back(Vec3::Zero());
      radii.push_back(q);
      break;
    case ShapeConfig::Kind::Clump:
      for (std::size_t k = 0; k < shape.clump->radii.size(); ++k) {
        centres.push_back(q * shape.clump->centres[k]);
        radii.push_back(q * shape.clump->radii[k]);
      }
      break;
    case ShapeConfig::Kind::Ellipsoid: ellipsoid_cover(q * shape.axes_rel, centres, radii); break;
  }
}

}  // namespace grains::sim::insert
