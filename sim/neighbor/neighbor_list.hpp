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
// 2 max|x - x_build| > skin (pairs) or max|x - x_build| + wall travel > skin,
// each with the radius growth since the build added to the displacement.
#include <algorithm>
#include <cstdint>
#include <utility>
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
  /// The largest skin of any pair (configure's): ghosts, wall near lists and
  /// checkpoints use it.
  double skin() const { return skin_; }
  /// A skin per grain (neighbor.skin_per_grain; 0: off): the pair (i, j) is
  /// listed within ri + rj + min(f (ri + rj), skin()), i.e. each grain has a
  /// skin of f times its own diameter, and the trigger asks each grain to have
  /// moved less than half its own skin. Small grains of a wide size
  /// distribution then keep small lists; the skin of the largest is skin().
  void set_skin_fraction(double f) { skin_fraction_ = f; }
  double skin_fraction() const { return skin_fraction_; }
  /// The smallest skin of any pair at the last build (the skin, without a
  /// skin per grain): what an integrator must not let two grains close.
  double smallest_skin() const { return skin_fraction_ > 0 ? smallest_skin_ : skin_; }
  /// How far apart (m, beyond touching) a contact may still hold: a normal
  /// law whose contacts outlive touching (JKR) sets its largest pull-off
  /// separation. The lists, the wall near lists and the force loop's first
  /// rejection reach this much further than the skin; 0 for every other law.
  void set_reach(double reach) { reach_ = reach; }
  /// Scenes with frozen grains (inv_mass 0): pairs of two frozen grains are
  /// left out, a contact with one has m* = the other's mass, and frozen
  /// grains are left out of the walls' near lists. Off: none of this runs.
  void set_frozen(bool on) { frozen_ = on; }
  /// Lees–Edwards boundaries: the speed of the sheared images relative to
  /// the cell, which closes the skin between a grain and an image too.
  void set_image_speed(double u) { image_speed_ = u; }
  double image_speed() const { return image_speed_; }
  /// Periodic images moved by d beyond that speed since the build (a
  /// Lees–Edwards cell whose height a servo changes): counted by the trigger.
  void add_image_travel(double d) { image_travel_ += d; }
  bool frozen() const { return frozen_; }
  double reach() const { return reach_; }
  int history_size() const { return history_size_; }

  /// True when the list no longer covers every pair that may touch.
  bool needs_rebuild(const ParticleStore& p, const Walls& walls, double time) const;
  /// Makes the next needs_rebuild() true: for an integrator that knows its
  /// coming steps may move particles further than the skin allows.
  void invalidate() { x_build_.clear(); }
  /// Owned particles were appended after the last build (inserted grains,
  /// no ghosts present): gives them empty rows, so that the list keeps
  /// matching the particles (a checkpoint of this step restores), and
  /// invalidates it, so that the next step builds their pairs.
  void append_empty_rows(std::size_t count) {
    if (!row_start.empty()) row_start.resize(row_start.size() + count, row_start.back());
    invalidate();
  }

  /// Radii grew by up to dr since the last build (integrate/radius_growth):
  /// the growth closes gaps like displacement does and counts in the trigger.
  void add_growth(double dr) { growth_ += dr; }

  /// Rebuilds rows, re-sorts particles by cell for locality (when sort is
  /// true; only without ghosts) and carries the contact history over. lo/hi
  /// bound the grid. With ghosts present, rows cover owned and ghost
  /// particles (a pair lives in the row of its smaller global id, whichever
  /// side is the ghost); ghost-ghost pairs are left out.
  void build(ParticleStore& p, const Walls& walls, const Vec3& lo, const Vec3& hi, double time, bool sort);
  /// Re-sorts the owned particles by cell (before ghosts are built).
  void sort_by_cell(ParticleStore& p, const Vec3& lo, const Vec3& hi) const;

  /// Calls fn(id_a, id_b, history) for every entry of the last build whose
  /// history is not all zero (id_a < id_b: the pair's ids).
  template <class Fn>
  void for_each_history(Fn&& fn) const {
    const std::size_t H = static_cast<std::size_t>(history_size_);
    if (H == 0 || build_id_.empty()) return;
    for (std::size_t r = 0; r + 1 < row_start.size(); ++r)
      for (auto k = row_start[r]; k < row_start[r + 1]; ++k) {
        const double* h = history.data() + k * H;
        bool any = false;
        for (std::size_t c = 0; c < H; ++c) any = any || h[c] != 0.0;
        if (any) fn(build_id_[r], build_id_[partner[k]], h);
      }
  }
  /// The ghosts were renumbered after the build: ghost n_owned + g is now
  /// to[g], or gone (kGone: a ghost in no entry, whose row is empty);
  /// `count` particles remain. Rows, partners and the build's ids follow.
  static constexpr std::uint32_t kGone = ~std::uint32_t{0};
  void renumber_ghosts(std::size_t n_owned, const std::vector<std::uint32_t>& to, std::size_t count);
  /// History of a pair from elsewhere (a migrating particle's contacts),
  /// used by the next build when the pair is in the list.
  void import_history(std::int64_t id_a, std::int64_t id_b, const double* h);
  /// Entries of the last build in which each particle takes part, for the
  /// ordered force sum (Scene::deterministic): for particle i, gather
  /// entries [gather_start[i], gather_start[i+1]) of gather_entry, each
  /// 2 k + (1 if i is the partner of entry k, 0 if its row), sorted by the
  /// other particle's global id. Built by build() when `with_gather` is set.
  void set_gather(bool on) { with_gather_ = on; }
  std::vector<std::uint32_t> gather_start, gather_entry;

  // Rows over owned particles: entries [row_start[i], row_start[i+1]).
  std::vector<std::uint32_t> row_start;
  std::vector<std::uint32_t> partner;   // local index of the other particle
  std::vector<double> history;          // history_size per entry
  /// Per entry: 0 only when the pair is known apart with zero history, so
  /// that the force loops skip the history of pairs that stay apart. (A
  /// cache: 1 after every build and restore, which only re-zeroes zero
  /// history.) Nothing else is kept per entry beside partner and history:
  /// the pair's contact distance, R* and m* are computed from the particles
  /// where they are needed (one byte per entry instead of 32, issue 26).
  std::vector<std::uint8_t> may_touch;
  /// The centre distance below which the pair (i, j) is in contact: ri + rj,
  /// plus the reach of a law whose contacts hold in tension (JKR).
  double contact_distance(const ParticleStore& p, std::size_t i, std::size_t j) const {
    return p.radius[i] + p.radius[j] + reach_;
  }
  /// R* = ri rj / (ri + rj).
  static double pair_radius(const ParticleStore& p, std::size_t i, std::size_t j) {
    return p.radius[i] * p.radius[j] / (p.radius[i] + p.radius[j]);
  }
  /// m* = mi mj / (mi + mj); with frozen grains (set_frozen), a frozen grain
  /// is as heavy as a wall: m* is the other's mass.
  double pair_mass(const ParticleStore& p, std::size_t i, std::size_t j) const {
    if (frozen_) {
      if (p.inv_mass[i] == 0) return p.mass[j];
      if (p.inv_mass[j] == 0) return p.mass[i];
    }
    return p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
  }
  /// Per wall (Walls' index across kinds): the owned particles near it.
  std::vector<std::vector<std::uint32_t>> wall_near;
  /// Per wall, what its kind keeps per near particle (a mesh: the triangles near it).
  std::vector<NearItems> wall_items;

  const Stats& stats() const { return stats_; }
  /// Bytes the list holds, by part (memory report): (name, bytes).
  std::vector<std::pair<const char*, std::size_t>> memory_parts() const;
  /// A continuation's first full update repeats the one the uninterrupted
  /// run made before saving: it keeps the saved count.
  void keep_build_count(long builds) { stats_.builds = builds; }

  /// What a build leaves besides the rows: the positions and time of the
  /// build (the displacement trigger), the ids of the rows (to carry history
  /// at the next build) and the build count. With row_start, partner, history
  /// and the wall near lists, this is all an exact restart needs.
  struct BuildState {
    double time = 0;
    std::vector<Vec3> x;
    std::vector<std::int64_t> row_id;
    long builds = 0;
    double growth = 0;  // radius growth since the build (add_growth)
  };
  BuildState build_state() const { return {build_time_, x_build_, build_id_, stats_.builds, growth_}; }
  /// Restores a saved list: the public rows, history and near lists must be
  /// assigned already; may_touch is set for every entry.
  void restore(const ParticleStore& p, BuildState b);

 private:
  void carry_history(const ParticleStore& p, const std::vector<std::uint32_t>& old_row_start,
                     const std::vector<std::uint32_t>& old_partner, const std::vector<double>& old_history);
  void build_gather(const ParticleStore& p);
  /// Candidate pairs of a wide size distribution: one cell grid per size
  /// class (radii within a factor 2), each sized by its own largest grain;
  /// pairs of a class among themselves by the half stencil of its grid, pairs
  /// with a larger class from each smaller grain into the larger class's grid
  /// (27 cells). The same pairs as one grid, found with far fewer candidates.
  template <bool Bodies, bool Ghosts>
  void collect_by_size_class(const ParticleStore& p, double rmin, double rmax, std::vector<std::uint32_t>& pi,
                             std::vector<std::uint32_t>& pj) const;
  /// The skin of the pair (i, j) in the list's cut-off.
  double pair_skin(const ParticleStore& p, std::size_t i, std::size_t j) const {
    return skin_fraction_ > 0 ? std::min(skin_fraction_ * (p.radius[i] + p.radius[j]), skin_) : skin_;
  }
  int history_size_ = 0;
  double skin_ = 0;
  double skin_fraction_ = 0;
  double smallest_skin_ = 0;
  double reach_ = 0;
  double build_time_ = 0;
  static void drop_frozen(const ParticleStore& p, std::vector<std::uint32_t>& near, NearItems& items);
  bool with_gather_ = false;
  bool frozen_ = false;
  double growth_ = 0;  // largest radius growth since the build
  double image_speed_ = 0;
  double image_travel_ = 0;
  std::vector<Vec3> x_build_;
  // Global ids of all particles (owned and ghosts) at the last build: the
  // keys that carry history to the next build.
  std::vector<std::int64_t> build_id_;
  // Histories received with migrating particles: (id_a, id_b) and H doubles each.
  std::vector<std::int64_t> imported_ids_;
  std::vector<double> imported_history_;
  Stats stats_;
};

}  // namespace grains::sim
