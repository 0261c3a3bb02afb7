#pragma once
// Verlet neighbour lists built on a linked-cell grid, with a skin.
//
// Pairs are kept once (a half list) in compressed rows: the pair {a, b} lives
// in the row of whichever particle has the smaller global id, so a pair
// always lands in the same row however the particles are re-sorted or
// migrated. Contact history is stored beside the list entries (history_size
// doubles each) and carried across rebuilds by matching global ids.
// Walls get near lists (particles within r + skin of the surface).
//
// The list is rebuilt when a particle may have closed the skin:
// 2 max|x - x_build| > skin (pairs) or max|x - x_build| + wall travel > skin.
#include <cstdint>
#include <vector>

#include "sim/state/particle_store.hpp"
#include "sim/walls/walls.hpp"

namespace grains::sim {

class NeighborList {
 public:
  struct Stats {
    long builds = 0;
    std::size_t pairs = 0;
  };

  void configure(int history_size, double skin) {
    history_size_ = history_size;
    skin_ = skin;
  }
  double skin() const { return skin_; }
  int history_size() const { return history_size_; }

  /// True when the list no longer covers every pair that may touch.
  bool needs_rebuild(const ParticleStore& p, const Walls& walls, double time) const;

  /// Rebuilds rows, re-sorts particles by cell for locality (when sort is
  /// true) and carries the contact history over. lo/hi bound the grid;
  /// particles outside must have been removed before.
  void build(ParticleStore& p, const Walls& walls, const Vec3& lo, const Vec3& hi, double time, bool sort);

  // Rows over owned particles: entries [row_start[i], row_start[i+1]).
  std::vector<std::uint32_t> row_start;
  std::vector<std::uint32_t> partner;   // local index of the other particle
  std::vector<double> history;          // history_size per entry
  /// Per-entry constants of a sphere pair, computed at build time: the
  /// squared contact distance (ri + rj)^2, R* and m*. They never change
  /// between builds, so the force loop does no divisions for them.
  /// `may_touch` is false only when the pair is known apart with zero
  /// history, so the force loop skips its history for non-touching pairs.
  struct PairConstants {
    double contact2, radius, mass;
    bool may_touch;
  };
  std::vector<PairConstants> pair_constants;
  std::vector<std::vector<std::uint32_t>> plane_near, cylinder_near;  // per wall

  const Stats& stats() const { return stats_; }

  /// What a build leaves besides the rows: the positions and time of the
  /// build (the displacement trigger), the ids of the rows (to carry history
  /// at the next build) and the build count. With row_start, partner, history
  /// and the wall near lists, this is all an exact restart needs.
  struct BuildState {
    double time = 0;
    std::vector<Vec3> x;
    std::vector<std::int64_t> row_id;
    long builds = 0;
  };
  BuildState build_state() const { return {build_time_, x_build_, old_row_id_, stats_.builds}; }
  /// Restores a saved list: the public rows, history and near lists must be
  /// assigned already; pair_constants are recomputed from the particles.
  void restore(const ParticleStore& p, BuildState b);

 private:
  void carry_history(const ParticleStore& p);
  void compute_pair_constants(const ParticleStore& p);
  int history_size_ = 0;
  double skin_ = 0;
  double build_time_ = 0;
  std::vector<Vec3> x_build_;
  // Previous build, keyed by global ids, for carrying history over.
  std::vector<std::int64_t> old_row_id_, old_partner_id_;
  std::vector<std::uint32_t> old_row_start_;
  std::vector<double> old_history_;
  std::vector<std::int32_t> row_of_id_;
  Stats stats_;
};

}  // namespace grains::sim
