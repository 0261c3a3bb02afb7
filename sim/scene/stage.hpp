#pragma once
// One stage of the step pipeline. A stage exists only when the scene needs
// it; the pipeline calls its run() once per step in its phase's order.
#include <memory>
#include <string>
#include <cstdint>
#include <utility>
#include <vector>

#include "sim/scene/scene.hpp"

namespace grains::sim {

class Pipeline;

/// What a restart from a checkpoint tells the output stages about the run
/// so far (io/checkpoint).
struct RestartPoint {
  std::string checkpoint;                 // the file the run continues from
  std::vector<double> frame_times;        // frames written before it
  std::vector<std::int64_t> frame_steps;
};

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
  /// Before the first step of a fresh run, after the forces at t0 (an output
  /// writes its record of t0)...
  virtual void start(Scene&) {}
  /// ...or instead, when the run continues from a checkpoint (an output
  /// takes up its series where the checkpoint left it).
  virtual void restart(Scene&, const RestartPoint&) {}
  /// A driver is an integrator that evaluates the neighbour and force phases
  /// itself, as often as it needs (an adaptive Runge-Kutta method evaluates
  /// the forces at its trial states). It sits in the drift phase; the
  /// pipeline calls drive() instead of run(), and step() then runs no other
  /// phase before the output phase.
  virtual bool is_driver() const { return false; }
  virtual void drive(Scene& s, Pipeline&) { run(s); }
  /// Output phase: whether run(), at the step the clock now shows, reads the
  /// particles' velocities or changes the particles (a frame, a check, a
  /// checkpoint, an insertion). The default says it does. At a step where no
  /// output stage does, Pipeline::step may leave the second half kick
  /// waiting for the next step's drift (see can_wait()).
  virtual bool reads_state(const Scene&) const { return true; }
  /// A kick-phase stage that may leave its work to the next step's drift
  /// phase, which then reads each grain's fields once for both half kicks
  /// (the Verlet kick of spheres). Only when it is the kick phase's one stage.
  virtual bool can_wait() const { return false; }
  /// Leaves this step's work waiting (can_wait() stages only).
  virtual void wait(Scene&) {}
  /// Does now any work left waiting (the run pauses, a checkpoint is taken).
  virtual void settle(Scene&) {}
  /// Extra figures for summary.json, as the members of a JSON object
  /// ("\"key\": value, ..."); empty when the stage has none.
  virtual std::string summary_json() const { return {}; }
  /// Memory the stage itself holds, by part (summary.json's memory block):
  /// e.g. the per-entry forces of ordered sums. Empty when it holds none.
  virtual std::vector<std::pair<std::string, double>> memory_parts() const { return {}; }
};

class Pipeline {
 public:
  void add(std::unique_ptr<Stage> s);
  /// Neighbour and force phases once, so that the first kick sees f(t0)
  /// (with clock.dt = 0 meanwhile: the contact history does not advance).
  void initialize(Scene& s);
  /// One time step: drift, neighbour, force, kick, clock, output. With a
  /// driver stage: the driver (which runs the other phases itself), clock, output.
  /// With `may_wait`, the kick may be left to the next step's drift when no
  /// output stage reads the state at this step (Stage::can_wait): the state
  /// between two steps is then complete only after settle(). The results are
  /// the same bits either way.
  void step(Scene& s, bool may_wait = false);
  /// Completes work left waiting by step(s, true) (a no-op when none waits).
  void settle(Scene& s);
  /// Runs the stages of one phase (timed), e.g. the force phase at a driver's trial state.
  void run_phase(Scene& s, Phase p);
  void finish(Scene& s);
  /// Every stage's start() (a fresh run) or restart() (a continued one), in order.
  void start(Scene& s);
  void restart(Scene& s, const RestartPoint& r);
  std::vector<std::string> stage_names() const;
  const std::vector<std::unique_ptr<Stage>>& stages() const { return stages_; }
  /// Wall-clock seconds spent in each stage so far (same order as stages()).
  /// Exclusive: a driver's time does not include the stages it ran.
  const std::vector<double>& stage_seconds() const { return seconds_; }

 private:
  void run_timed(std::size_t k, Scene& s);
  std::vector<std::unique_ptr<Stage>> stages_;
  std::vector<double> seconds_;
  double nested_ = 0;  // seconds of the stages run inside the current one
  int driver_ = -1;    // index of the driver stage, or -1
  int waiter_ = -1;    // index of the kick phase's one stage when it can wait, or -1
};

}  // namespace grains::sim
