#include "postprocess/frame_packing.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include "postprocess/cell_grid.hpp"

namespace grains::postprocess {

namespace {

bool inside(const Vec3& p, const Box& b) {
  return (p.array() >= b.lo.array()).all() && (p.array() <= b.hi.array()).all();
}

bool cube_meets(const Vec3& c, double h, const Box& b) {
  return ((c.array() + h) > b.lo.array()).all() && ((c.array() - h) < b.hi.array()).all();
}

bool cube_within(const Vec3& c, double h, const Box& b) {
  return ((c.array() - h) >= b.lo.array()).all() && ((c.array() + h) <= b.hi.array()).all();
}

}  // namespace

bool exact_spheres(const Frame& f) { return !f.has_ellipsoids() && f.body.empty(); }

std::vector<VolumeEstimate> union_volume_in_boxes(const Frame& f, const std::vector<Box>& boxes,
                                                  const SamplingOptions& o) {
  const std::size_t n = f.size(), nb = boxes.size();
  std::vector<VolumeEstimate> out(nb);
  if (n == 0 || nb == 0) return out;
  const std::size_t M = std::max<std::size_t>(o.samples_per_particle, 2);
  const bool ell = f.has_ellipsoids();
  std::vector<Eigen::Matrix3d> rt;  // world -> body, rows scaled by 1/a
  if (ell) {
    rt.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Matrix3d R = f.has_orientation() ? f.orientation[i].toRotationMatrix() : Eigen::Matrix3d::Identity();
      rt[i] = f.semi_axes[i].cwiseInverse().asDiagonal() * R.transpose();
    }
  }
  auto contains = [&](std::size_t j, const Vec3& p) {
    const Vec3 d = p - f.x[j];
    if (!ell) return d.squaredNorm() <= f.radius[j] * f.radius[j];
    return (rt[j] * d).squaredNorm() <= 1.0;
  };
  double bmax = 0;
  for (std::size_t i = 0; i < n; ++i) bmax = std::max(bmax, f.bounding_radius(i));
  const CellGrid grid(f.x, 2 * bmax);
  std::vector<double> var(nb, 0.0), s1(nb), s2(nb);
  std::vector<std::size_t> near_boxes, others;
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double bi = f.bounding_radius(i);
    near_boxes.clear();
    for (std::size_t k = 0; k < nb; ++k)
      if (cube_meets(f.x[i], bi, boxes[k])) near_boxes.push_back(k);
    if (near_boxes.empty()) continue;
    others.clear();
    grid.for_each_near(f.x[i], bi + bmax, [&](std::size_t j) {
      if (j == i) return;
      const double reach = bi + f.bounding_radius(j);
      if ((f.x[j] - f.x[i]).squaredNorm() < reach * reach) others.push_back(j);
    });
    const double V = f.particle_volume(i);
    if (others.empty() && near_boxes.size() == 1 && cube_within(f.x[i], bi, boxes[near_boxes[0]])) {
      out[near_boxes[0]].volume += V;
      continue;
    }
    for (std::size_t k : near_boxes) s1[k] = s2[k] = 0;
    const Eigen::Matrix3d body_to_world =
        ell ? Eigen::Matrix3d((f.has_orientation() ? f.orientation[i].toRotationMatrix() : Eigen::Matrix3d::Identity()) *
                              f.semi_axes[i].asDiagonal())
            : Eigen::Matrix3d(f.radius[i] * Eigen::Matrix3d::Identity());
    for (std::size_t s = 0; s < M; ++s) {
      Vec3 q;
      do q = Vec3(u(rng), u(rng), u(rng));
      while (q.squaredNorm() > 1.0);
      const Vec3 p = f.x[i] + body_to_world * q;
      int cover = 1;
      for (std::size_t j : others)
        if (contains(j, p)) ++cover;
      const double y = 1.0 / cover;
      for (std::size_t k : near_boxes)
        if (inside(p, boxes[k])) {
          s1[k] += y;
          s2[k] += y * y;
        }
    }
    const double m = static_cast<double>(M);
    for (std::size_t k : near_boxes) {
      const double mean = s1[k] / m;
      const double sample_var = std::max(0.0, (s2[k] - m * mean * mean) / (m - 1));
      out[k].volume += V * mean;
      var[k] += V * V * sample_var / m;
    }
  }
  for (std::size_t k = 0; k < nb; ++k) out[k].error = std::sqrt(var[k]);
  return out;
}

PackingEstimate packing_fraction(const Frame& f, const Box& region, const SamplingOptions& o) {
  if (!(region.volume() > 0)) throw std::invalid_argument("packing fraction: the region has no volume");
  PackingEstimate e;
  if (exact_spheres(f)) {
    e.phi = packing_fraction(f.x, f.radius, region);
    e.exact = true;
    e.method = "exact sphere-box intersection";
    return e;
  }
  const auto v = union_volume_in_boxes(f, {region}, o);
  e.phi = v[0].volume / region.volume();
  e.error = v[0].error / region.volume();
  e.method = "Monte Carlo union volume, " + std::to_string(o.samples_per_particle) + " points per particle";
  return e;
}

PhiProfile phi_profile(const Frame& f, const Box& span, int axis, double bin, const SamplingOptions& o) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("profile axis must be 0, 1 or 2 (x, y, z)");
  if (!(bin > 0)) throw std::invalid_argument("profile bin width must be positive");
  PhiProfile p;
  p.axis = axis;
  std::vector<Box> slabs;
  for (double a = span.lo[axis]; a < span.hi[axis] - 1e-12 * bin; a += bin) {
    Box b = span;
    b.lo[axis] = a;
    b.hi[axis] = std::min(a + bin, span.hi[axis]);
    slabs.push_back(b);
    p.lo.push_back(b.lo[axis]);
    p.hi.push_back(b.hi[axis]);
  }
  p.phi.assign(slabs.size(), 0.0);
  p.error.assign(slabs.size(), 0.0);
  if (exact_spheres(f)) {
    p.exact = true;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const double c = f.x[i][axis], r = f.radius[i];
      const auto first = static_cast<long>(std::floor((c - r - span.lo[axis]) / bin));
      const auto last = static_cast<long>(std::floor((c + r - span.lo[axis]) / bin));
      for (long k = std::max(0L, first); k <= last && k < static_cast<long>(slabs.size()); ++k)
        p.phi[static_cast<std::size_t>(k)] += sphere_box_volume(f.x[i], r, slabs[static_cast<std::size_t>(k)]);
    }
    for (std::size_t k = 0; k < slabs.size(); ++k) p.phi[k] /= slabs[k].volume();
    return p;
  }
  const auto v = union_volume_in_boxes(f, slabs, o);
  for (std::size_t k = 0; k < slabs.size(); ++k) {
    p.phi[k] = v[k].volume / slabs[k].volume();
    p.error[k] = v[k].error / slabs[k].volume();
  }
  return p;
}

Box particle_bounds(const Frame& f) {
  if (f.size() == 0) throw std::runtime_error("the frame has no particles");
  Box b{f.x[0], f.x[0]};
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double r = f.bounding_radius(i);
    b.lo = b.lo.cwiseMin(f.x[i] - Vec3::Constant(r));
    b.hi = b.hi.cwiseMax(f.x[i] + Vec3::Constant(r));
  }
  return b;
}

Box auto_bulk_region(const Frame& f, double margin_diameters) {
  const Box bounds = particle_bounds(f);
  const double margin = margin_diameters * f.mean_diameter();
  const Box b = bulk_region(f.x, f.radius, bounds, margin);
  if (!((b.hi - b.lo).array() > 0).all()) {
    std::ostringstream m;
    m << "no bulk region: the particles span [" << bounds.lo.transpose() << "] to [" << bounds.hi.transpose()
      << "], too small for a margin of " << margin << " m (" << margin_diameters
      << " diameters) from the sides, floor and free surface; give --region or a smaller --margin";
    throw std::runtime_error(m.str());
  }
  return b;
}

}  // namespace grains::postprocess
