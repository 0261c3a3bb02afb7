#pragma once
// Isotropic compression by growing radii (a jamming protocol): every radius
// is multiplied by exp(g dt) each step, with the relative rate g servo-
// controlled towards a target overlap per particle,
//
//   g = rate * clamp(1 - o / target_overlap, -1, 1),
//   o = (1/N) sum over touching pairs of delta_ij / (r_i + r_j),
//
// so the packing grows at `rate` while it is loose, slows down as contacts
// carry load and settles where o = target_overlap (o ~ Z/2 times the mean
// relative overlap of a contact: a proxy of the pressure that is zero in a
// loose packing and small in a just-jammed one). Radii shrink back when the
// packing is compressed beyond the target. A schedule of phases (rate and
// target until a time; rate 0 holds the radii while the packing relaxes)
// runs a whole protocol from one case file.
//
// Masses keep the material's density (m ~ r^3, rotational inertia ~ m r^2),
// so the Rayleigh time grows with the radius and the time step chosen for
// the initial radii stays safe. The neighbour list's per-pair constants are
// refreshed after each growth, and its rebuild trigger includes the growth
// since the last build (NeighborList::add_growth). Radii grow to at most
// max_scale times the smallest initial radius (the ghost cut-off of periodic
// and parallel runs is sized for it). Spheres only (set-up refuses
// ellipsoids and clumps). Case-file keys: radius_growth.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sim/scene/stage.hpp"

namespace grains::sim {

/// One phase of a compression schedule: the servo's rate and target until
/// the simulated time `until`.
struct GrowthPhase {
  double rate = 0;  // 1/s; 0: radii fixed (the packing relaxes)
  double target_overlap = 0;
  double until = 0;  // s
};

struct RadiusGrowthConfig {
  bool enabled = false;
  double rate = 0;              // 1/s: largest relative growth rate d ln r / dt
  double target_overlap = 0;    // overlap per particle o at which growth stops
  /// A schedule instead of (rate, target_overlap): each phase applies until
  /// its time; after the last one the radii stay fixed.
  std::vector<GrowthPhase> phases;
  std::int64_t every_steps = 10;  // steps between measurements of o
  double max_scale = 2;         // radii grow to at most this times initial_radius
  double initial_radius = 0;    // the smallest radius of the case (set at set-up)
};

class RadiusGrowth final : public Stage {
 public:
  explicit RadiusGrowth(RadiusGrowthConfig c) : c_(std::move(c)) {}
  std::string name() const override { return "compress.grow_radii(servo on overlap per particle)"; }
  Phase phase() const override { return Phase::Drift; }
  /// The servo's state between steps lives in the scene (Scene::growth), so
  /// that checkpoints save it with the rest of the state.
  void run(Scene& s) override;
  /// The overlap per particle o of the current state (pairs of the neighbour
  /// list). Summed in fixed point, so the value does not depend on the order
  /// of the pairs (list order, rank decomposition): a restarted or parallel
  /// run measures exactly the same o.
  static double overlap_per_particle(const Scene& s);
  const RadiusGrowthConfig& config() const { return c_; }
  /// True once growth stopped at max_scale (the packing did not jam before).
  bool capped() const { return capped_; }

 private:
  RadiusGrowthConfig c_;
  bool capped_ = false;  // mirror of Scene::growth.capped for callers without the scene
};

}  // namespace grains::sim
