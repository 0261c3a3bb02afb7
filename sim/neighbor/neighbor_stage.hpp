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
  static void full_update(Scene& s, bool sort);

 private:
  bool sort_;
};

}  // namespace grains::sim
