#pragma once
// Plain inputs of the overlap fields: a set of balls and a grid of nodes.
// Nothing here depends on the simulator; callers pass views of their arrays.
#include <array>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <string>

namespace grains::correlation {

// n balls: centres interleaved (x0, y0, z0, x1, ...), radii, optional weights
// (empty = all 1). The fields are sums of weighted ball indicators, so balls
// that overlap each other (inside a clump, say) count their shared volume
// once per ball; give such balls weights that restore the intended volume, or
// read the field as "sum of ball indicators" rather than solid fraction.
struct BallSet {
  std::span<const double> centres;
  std::span<const double> radii;
  std::span<const double> weights = {};

  std::size_t size() const { return radii.size(); }
  double weight(std::size_t i) const { return weights.empty() ? 1.0 : weights[i]; }

  void validate(const char* who) const {
    if (centres.size() != 3 * radii.size())
      throw std::invalid_argument(std::string(who) + ": centres must hold 3 numbers per radius (" +
                                  std::to_string(centres.size()) + " for " +
                                  std::to_string(radii.size()) + " radii)");
    if (!weights.empty() && weights.size() != radii.size())
      throw std::invalid_argument(std::string(who) + ": weights must be empty or one per ball");
    for (double r : radii)
      if (!(r > 0.0)) throw std::invalid_argument(std::string(who) + ": radii must be positive");
  }
};

// Nodes origin + i * spacing, i_d = 0 .. dims_d - 1, values stored x fastest
// (index (i2 * dims1 + i1) * dims0 + i0), as VTK image data expects. Along a
// periodic axis the period is dims_d * spacing_d; along a non-periodic axis
// the box is padded internally so that nothing wraps around.
struct GridSpec {
  std::array<double, 3> origin{0.0, 0.0, 0.0};
  std::array<double, 3> spacing{1.0, 1.0, 1.0};
  std::array<int, 3> dims{1, 1, 1};
  std::array<bool, 3> periodic{true, true, true};

  std::size_t num_nodes() const {
    return static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  }
  std::array<double, 3> node(std::size_t idx) const {
    const std::size_t i0 = idx % dims[0], i1 = (idx / dims[0]) % dims[1],
                      i2 = idx / (static_cast<std::size_t>(dims[0]) * dims[1]);
    return {origin[0] + i0 * spacing[0], origin[1] + i1 * spacing[1], origin[2] + i2 * spacing[2]};
  }
  void validate(const char* who) const {
    for (int d = 0; d < 3; ++d)
      if (dims[d] < 1 || !(spacing[d] > 0.0))
        throw std::invalid_argument(std::string(who) +
                                    ": grid needs dims >= 1 and spacing > 0 on every axis");
  }
};

}  // namespace grains::correlation
