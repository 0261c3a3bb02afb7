#pragma once
// Packing fraction of a frame in a region, and its profile along an axis.
//
// Spheres (no semi_axes, no clump `body`): exact, through sphere_box_volume
// (packing_fraction.hpp); DEM contact overlaps (a fraction of a percent of a
// diameter) are counted twice there, which the report states.
//
// Ellipsoids and clump balls: Monte Carlo on each particle. For particle i
// with volume V_i, M points p are drawn uniformly inside it and each adds
// V_i / M * 1[p in box] / c(p) to the box, where c(p) >= 1 is the number of
// particles that contain p. Summed over particles this estimates the volume of
// the *union* of the shapes inside the box, so overlapping balls of a clump
// (and contact overlaps) count once. A particle whose bounding sphere lies
// inside one box and meets no other bounding sphere adds V_i exactly. The
// error bar is one standard deviation of the estimate:
//     sigma^2 = sum_i V_i^2 s_i^2 / M,
// s_i^2 the sample variance of 1[p in box]/c(p) over particle i's points
// (independent particles, so variances add); divided by the box volume.
#include <cstdint>
#include <string>
#include <vector>

#include "postprocess/frame.hpp"
#include "postprocess/packing_fraction.hpp"

namespace grains::postprocess {

struct SamplingOptions {
  std::size_t samples_per_particle = 1000;
  std::uint64_t seed = 1;
};

struct VolumeEstimate {
  double volume = 0;  // m^3
  double error = 0;   // one standard deviation, m^3
};

/// Volume of the union of the frame's particles inside each box, by sampling.
std::vector<VolumeEstimate> union_volume_in_boxes(const Frame& f, const std::vector<Box>& boxes,
                                                  const SamplingOptions& o = {});

/// True when the exact sphere path applies (spheres, not clump balls).
bool exact_spheres(const Frame& f);

struct PackingEstimate {
  double phi = 0;
  double error = 0;  // one standard deviation (0 for the exact path, up to quadrature rounding)
  bool exact = false;
  std::string method;  // "exact sphere-box intersection" or "Monte Carlo union volume"
};

PackingEstimate packing_fraction(const Frame& f, const Box& region, const SamplingOptions& o = {});

struct PhiProfile {
  int axis = 2;
  std::vector<double> lo, hi, phi, error;
  bool exact = false;
};

/// phi in slabs of width `bin` along `axis` (0, 1, 2) across `span`; the last
/// slab may be narrower.
PhiProfile phi_profile(const Frame& f, const Box& span, int axis, double bin, const SamplingOptions& o = {});

/// Box holding every particle (centres +- bounding radius).
Box particle_bounds(const Frame& f);

/// Automatic bulk region of a bed settled along -z: `margin_diameters` mean
/// diameters away from the particle bounds at the sides and bottom (walls are
/// where the particles end) and from the free surface (bulk_region()).
/// Throws std::runtime_error when the margins leave no region.
Box auto_bulk_region(const Frame& f, double margin_diameters = 2.0);

}  // namespace grains::postprocess
