#pragma once
// One stage of the step pipeline. A stage exists only when the scene needs
// it; the pipeline calls its run() once per step in its phase's order.
#include <memory>
#include <string>
#include <vector>

#include "sim/scene/scene.hpp"

namespace grains::sim {

enum class Phase {
  Drift,     // first half kick + drift, wall motion
  Neighbor,  // neighbour list upkeep
  Force,     // force accumulation
  Kick,      // second half kick
  Output,    // writers, progress, checks (after the clock advanced)
};

const char* phase_name(Phase p);

class Stage {
 public:
  virtual ~Stage() = default;
  virtual std::string name() const = 0;
  virtual Phase phase() const = 0;
  virtual void run(Scene& s) = 0;
  /// Called once after the last step (writers flush, summaries).
  virtual void finish(Scene&) {}
};

class Pipeline {
 public:
  void add(std::unique_ptr<Stage> s);
  /// Neighbour and force phases once, so that the first kick sees f(t0).
  void initialize(Scene& s);
  /// One time step: drift, neighbour, force, kick, clock, output.
  void step(Scene& s);
  void finish(Scene& s);
  std::vector<std::string> stage_names() const;
  const std::vector<std::unique_ptr<Stage>>& stages() const { return stages_; }
  /// Wall-clock seconds spent in each stage so far (same order as stages()).
  const std::vector<double>& stage_seconds() const { return seconds_; }

 private:
  void run_phase(Scene& s, Phase p);
  void run_timed(std::size_t k, Scene& s);
  std::vector<std::unique_ptr<Stage>> stages_;
  std::vector<double> seconds_;
};

}  // namespace grains::sim
