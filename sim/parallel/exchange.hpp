#pragma once
// Ghosts, migration and load balance of the domain decomposition, and the
// periodic images of a periodic box (which are the one-rank case of the
// same exchange: a rank is its own neighbour across a periodic face).
//
// Full update (at a neighbour-list rebuild, decided for all ranks at once):
//   wrap periodic positions -> rebalance if the load is uneven -> migrate
//   owned particles to the rank owning their position (a clump's balls go
//   with the rank of its centre of mass), with the contact history of every
//   pair they take part in -> sort by cell -> build ghosts -> build lists.
// Cheap update (every other step): the ghosts' kinematics are refreshed
// along the same send lists.
//
// Ghosts are built in three stages (x, then y, then z); each stage sends to
// the two face neighbours the particles (owned, and ghosts received in the
// earlier stages) within the ghost cut-off of the face, so edge and corner
// neighbours are reached without diagonal messages. Contacts between an
// owned particle and a ghost are computed on both ranks (the pair's force
// lands on each rank's own particle), with identical inputs, so both copies
// of the pair's history evolve identically and either can move with a
// migrating particle.
#include <array>
#include <cstdint>
#include <vector>

#include "sim/parallel/comm.hpp"
#include "sim/parallel/decomposition.hpp"
#include "sim/scene/scene.hpp"

namespace grains::sim {

struct ExchangeOptions {
  std::array<int, 3> dims{0, 0, 0};  // requested rank grid (0: choose)
  double balance_threshold = 1.1;    // rebalance when max/mean work per rank > this
  /// The largest radius the cut-off was made for (0: every grain uses the
  /// whole cut-off). A grain of radius r then goes to a neighbour within
  /// cut-off - largest_radius + r of the face: no partner of it there lies
  /// farther (wide size distributions: the small grains' ghosts are fewer).
  double largest_radius = 0;
};

class Exchange {
 public:
  struct Stats {
    long full_updates = 0, rebalances = 0;
    std::int64_t migrated = 0;  // particles sent to another rank, summed over updates
    std::size_t ghosts = 0;     // after the last full update
    std::size_t images_built = 0;  // ghosts built then, before drop_unlisted_images
    double imbalance = 1;       // max/mean estimated work per rank at the last full update
  };

  /// `cutoff`: the ghost cut-off (largest pair cut-off 2 r_max + skin, plus
  /// the largest distance of a clump ball from its centre of mass).
  Exchange(const Comm& comm, const Domain& domain, double cutoff, ExchangeOptions opt = {});

  const Comm& comm() const { return comm_; }
  const Decomposition& decomposition() const { return dec_; }
  double cutoff() const { return cut_; }
  const Stats& stats() const { return stats_; }

  /// Keeps only the particles and bodies this rank owns (every rank built
  /// the whole scene identically), after balancing the cuts on them; or,
  /// given the cuts a checkpoint saved for the same rank grid, with those
  /// cuts, and the next migrate() then keeps them too (so that a continued
  /// run owns, wraps and rebalances exactly as the uninterrupted one).
  void distribute_initial(Scene& s, const std::array<std::vector<double>, 3>* saved_cuts = nullptr);
  /// Wraps periodic positions, rebalances when needed and migrates owned
  /// particles and bodies (with contact histories) to their owners. No
  /// ghosts may be present. `work`: estimated cost of each owned particle
  /// (work_weights()), or null to count particles.
  void migrate(Scene& s, const std::vector<double>* work = nullptr) { migrate(s, work, s.clock.time); }
  /// The same for a state at `time` (inside a step: the clock's time + dt).
  void migrate(Scene& s, const std::vector<double>* work, double time);
  /// Estimated cost per step of each owned particle from the last list:
  /// one unit for the particle's own updates plus one per list entry it
  /// takes part in (half of an entry between two owned particles, a whole
  /// one against a ghost, which this rank computes alone). Measured on the
  /// 10k pour: a list entry costs about as much as a particle's integration
  /// and wall checks (bench/RESULTS.md). Call before ghosts are cleared.
  static std::vector<double> work_weights(const ParticleStore& p, const NeighborList& list);
  /// Builds the ghosts at time t and remembers the send lists (with
  /// Lees–Edwards boundaries the gradient's images first, displaced along
  /// the flow and moving relative to the cell).
  void build_ghosts(ParticleStore& p, double time);
  /// The domain's new height along the Lees–Edwards gradient (the pressure
  /// servo, or a restart of it): the cuts follow affinely, and the images
  /// across that axis are shifted by the new length from the next update.
  void set_domain(const Domain& d);
  /// Refreshes the ghosts' kinematics along the send lists, at time t.
  void update_ghosts(ParticleStore& p, double time);
  /// After the lists are built on these ghosts: drops the images this rank
  /// made of its own grains (a periodic axis it holds whole) that no list
  /// entry uses and that no kept image is made from, and renumbers the
  /// particles, the lists and the send lists. In a wide size distribution
  /// most images are small grains that reach across the face only as far as
  /// the largest grain's cut-off (bimodal10: a fifth of them are in the
  /// list); the ghost updates, the force clearing and the memory then carry
  /// only the rest. The same rows and entries in the same order: the same
  /// sums.
  void drop_unlisted_images(ParticleStore& p, NeighborList& list);
  /// Bytes held by the send lists and the message buffers (memory report;
  /// at their capacity: a buffer is written up to the largest message it held).
  std::size_t memory_bytes() const {
    std::size_t b = swaps_.capacity() * sizeof(Swap);
    for (int k = 0; k < 2; ++k) b += sbufs_[k].capacity() + rbufs_[k].capacity();
    for (const auto& sw : swaps_) b += sw.send.capacity() * sizeof(std::uint32_t) + sw.flow_wrap.capacity();
    return b;
  }

 private:
  struct Swap {
    int dest = -1, src = -1;
    Vec3 recv_shift{0, 0, 0};
    std::vector<std::uint32_t> send;
    std::size_t recv_start = 0, recv_count = 0;
    // Across a sheared face (Lees–Edwards): the side of the image (+1 above,
    // -1 below), the whole periods of the offset taken off at the build, and
    // each ghost's wrap along the flow then (in periods).
    int shear_side = 0;
    double offset_periods = 0;
    std::vector<signed char> flow_wrap;
  };
  /// A swap within this rank: its ghosts are copies of its own particles.
  bool local(const Swap& sw) const {
    return sw.src >= 0 && sw.send.size() == sw.recv_count &&
           (!comm_.parallel() || (sw.dest == comm_.rank() && sw.src == comm_.rank()));
  }
  /// The position along the flow of a ghost across the sheared face, from
  /// its source's x_f: continuous between builds.
  double sheared(const Swap& sw, double xf, signed char wrap, double time) const;
  void wrap(Scene& s, double time);
  const Comm& comm_;
  Domain domain_;
  Decomposition dec_;
  double cut_;
  bool ghosts_sized_ = false;  // build_ghosts has reserved room for the ghosts once
  ExchangeOptions opt_;
  bool keep_cuts_once_ = false;  // the next migrate() does not rebalance (restored cuts)
  std::vector<Swap> swaps_;
  std::array<std::vector<char>, 2> sbufs_, rbufs_;  // a dimension's two swaps' messages
  std::vector<Comm::Transfer> transfers_;
  Stats stats_;
};

}  // namespace grains::sim
