#pragma once
// Initial particle placement: random non-overlapping fill of a box region
// (random sequential addition, largest first), a simple cubic lattice, or
// positions read from a file. All placed particles, across sets, are checked
// against each other for overlaps beyond the tolerance.
#include <random>
#include <vector>

#include "sim/scene/scene_config.hpp"

namespace grains::sim {

struct PlacedParticle {
  Vec3 x;
  double r;
  int set;
  std::size_t index_in_set;
};

/// Draws `count` radii from a distribution (deterministic for a given rng).
std::vector<double> sample_radii(const SizeDistribution& d, std::int64_t count, std::mt19937_64& rng);

/// Places every set; throws SetupError naming the set's case-file location.
std::vector<PlacedParticle> place_particles(const SceneConfig& c);

/// Throws SetupError if two particles overlap by more than tol * smaller radius.
void check_overlaps(const SceneConfig& c, const std::vector<PlacedParticle>& p);

}  // namespace grains::sim
