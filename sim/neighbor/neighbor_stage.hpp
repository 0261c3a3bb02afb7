#pragma once
// Keeps the neighbour lists valid: checks the displacement trigger each step
// (over all ranks) and, when it fires, removes particles that left the
// domain, migrates particles between ranks, builds ghosts and rebuilds;
// otherwise it only refreshes the ghosts.
#include "sim/scene/stage.hpp"

namespace grains::sim {

class NeighborStage final : public Stage {
 public:
  explicit NeighborStage(bool sort_particles = true) : sort_(sort_particles) {}
  std::string name() const override { return "neighbor.verlet_list(skin trigger)"; }
  Phase phase() const override { return Phase::Neighbor; }
  void run(Scene& s) override;
  /// Lost particles out, migration, ghosts and lists, whatever the trigger
  /// says (also used at start and after a restart).
  /// Everything rebuilt for the state at `time` (inside a step the clock's
  /// time + dt: the clock moves on after the kick).
  /// With `canonical` (a checkpoint's step, and a continuation's first
  /// update) the grains are put in id order before the cell sort, so that
  /// both hold them in the same order whatever order they came in (sums over
  /// grains, frames and CSV series then round alike).
  static void full_update(Scene& s, bool sort, double time, bool canonical = false);
  static void full_update(Scene& s, bool sort, bool canonical = false) { full_update(s, sort, s.clock.time, canonical); }

 private:
  bool sort_;
};

}  // namespace grains::sim
