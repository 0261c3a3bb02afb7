#pragma once
// Spatial domain decomposition on a tensor-product grid of ranks whose cut
// planes move: rank (cx, cy, cz) owns [cuts_x[cx], cuts_x[cx+1]) x ... Cuts
// start uniform and are re-placed at quantiles of the particle positions
// when the load is uneven (a poured bed has most particles at the bottom),
// so every slab of a dimension holds about the same number of particles.
// Each slab is kept at least `min_width` (the ghost cut-off) wide, so ghosts
// only ever come from face neighbours (staged exchange, exchange.hpp).
#include <array>
#include <string>
#include <vector>

#include "sim/parallel/comm.hpp"
#include "sim/state/particle_store.hpp"

namespace grains::sim {

struct Domain;

class Decomposition {
 public:
  Decomposition() = default;
  /// Chooses the rank grid (or takes `requested` where its entries are > 0)
  /// minimising the cut area, with every slab at least min_width wide.
  /// Throws SetupError-like std::runtime_error when no grid fits.
  Decomposition(const Domain& d, int ranks, double min_width, std::array<int, 3> requested = {0, 0, 0});

  const std::array<int, 3>& dims() const { return dims_; }
  std::array<int, 3> coords(int rank) const;
  int rank_at(std::array<int, 3> c) const;
  /// The rank owning position x (x inside the domain, periodic dims wrapped).
  int owner(const Vec3& x) const;
  /// Face neighbour of `rank` in dimension d, direction dir (-1/+1), or -1
  /// at a non-periodic boundary. `wraps` tells if crossing wraps around.
  int neighbor(int rank, int d, int dir, bool& wraps) const;
  Vec3 lo(int rank) const;
  Vec3 hi(int rank) const;
  const std::array<std::vector<double>, 3>& cuts() const { return cuts_; }
  /// Takes cuts saved from a decomposition of the same grid (a checkpoint's,
  /// sim::Exchange::distribute_initial). Returns false, changing nothing,
  /// when their counts do not fit this grid or they are not increasing
  /// from the domain's low to its high side.
  bool set_cuts(const std::array<std::vector<double>, 3>& cuts);
  double min_width() const { return min_width_; }
  /// The domain's extent along k becomes [lo, hi] (a pressure-servoed
  /// Lees–Edwards cell): the cuts follow affinely. Throws std::runtime_error
  /// when a slab would become narrower than min_width.
  void resize(int k, double lo, double hi);

  /// Moves the cuts to quantiles of the owned positions of all ranks
  /// (a histogram reduced over ranks), each position counted with its
  /// weight (its estimated work; 1 each when weight is null). Returns true
  /// when cuts changed.
  bool balance(const std::vector<Vec3>& x, std::size_t n, const Comm& comm, const double* weight = nullptr);
  /// Largest load over the mean (1 = perfect balance); load = owned count.
  static double imbalance(std::size_t n_owned, const Comm& comm);
  /// The same for a load given as a number (e.g. the summed work weights).
  static double imbalance(double load, const Comm& comm);
  std::string describe() const;

 private:
  std::array<int, 3> dims_{1, 1, 1};
  std::array<std::vector<double>, 3> cuts_;
  std::array<bool, 3> periodic_{false, false, false};
  Vec3 lo_{0, 0, 0}, hi_{1, 1, 1};
  double min_width_ = 0;
};

}  // namespace grains::sim
