#pragma once
// Keeps the neighbour lists valid: checks the displacement trigger each step
// and, when it fires, removes particles that left the domain and rebuilds.
#include "sim/scene/stage.hpp"

namespace grains::sim {

class NeighborStage final : public Stage {
 public:
  explicit NeighborStage(bool sort_particles = true) : sort_(sort_particles) {}
  std::string name() const override { return "neighbor.verlet_list(skin trigger)"; }
  Phase phase() const override { return Phase::Neighbor; }
  void run(Scene& s) override;

 private:
  bool sort_;
};

}  // namespace grains::sim
