#pragma once
// Radial distribution function g(r) of particle centres in a region of a
// non-periodic sample. Reference particles are those whose centre lies at
// least r_max inside the region, so that every partner within r_max is
// counted (no edge correction needed); partners are all other centres.
//     g(r) = n(r) / (N_ref * rho * V_shell(r)),
// with n(r) the number of partners at distance [r, r + dr) summed over the
// references, rho = N_region / V_region the number density of the region and
// V_shell = 4/3 pi ((r + dr)^3 - r^3). For clump balls pass the clump centres.
#include <vector>

#include "postprocess/packing_fraction.hpp"

namespace grains::postprocess {

struct Rdf {
  std::vector<double> r;  // bin centres (m)
  std::vector<double> g;
  double bin = 0;
  double density = 0;             // centres per m^3 in the region
  std::size_t n_reference = 0;
  std::size_t n_region = 0;
};

/// Throws std::invalid_argument when no centre lies r_max inside the region.
Rdf radial_distribution(const std::vector<Vec3>& centres, const Box& region, double r_max, int bins);

/// Positions of the local maxima of g whose height exceeds `min_height`
/// (a bin higher than both neighbours), in increasing r.
std::vector<double> rdf_peaks(const Rdf& g, double min_height);

}  // namespace grains::postprocess
