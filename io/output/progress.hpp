#pragma once
// Output-phase stages for the person watching a run: a progress line on
// stderr, and a watchdog that stops a blown-up run with a diagnosis.
#include <chrono>
#include <ostream>
#include <string>

#include "sim/scene/stage.hpp"

namespace grains::io {

/// "step 12000/40000 (30.0%)  t = 0.1038 s  ETA 42 s  5.21e+06 particle-steps/s"
class Progress final : public sim::Stage {
 public:
  Progress(std::ostream& out, double interval_seconds);
  std::string name() const override { return "output.progress"; }
  sim::Phase phase() const override { return sim::Phase::Output; }
  void run(sim::Scene& s) override;
  void finish(sim::Scene& s) override;
  bool reads_state(const sim::Scene&) const override { return false; }  // the clock and the count only

 private:
  void print(const sim::Scene& s, bool final);
  std::ostream& out_;
  double interval_;
  std::chrono::steady_clock::time_point start_, last_;
  std::int64_t start_step_ = -1;
  double particle_steps_ = 0;
};

/// Thrown when the state is no longer physical; the message names the
/// particle, the step and the likely cause.
struct BlowUp : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Every `every` steps: positions and velocities finite, speeds below a bound
/// (100 times the largest speed a particle could reach by falling through
/// the domain or moving with the fastest wall, plus the initial speeds and
/// `extra_speed`, e.g. the growth rate of radii times the domain size), and
/// no pair overlapping by more than half the smaller radius.
class BlowUpCheck final : public sim::Stage {
 public:
  BlowUpCheck(const sim::Scene& s, double rayleigh_time, std::int64_t every = 200, double extra_speed = 0);
  std::string name() const override { return "check.blow_up(every " + std::to_string(every_) + " steps)"; }
  sim::Phase phase() const override { return sim::Phase::Output; }
  void run(sim::Scene& s) override;
  bool reads_state(const sim::Scene& s) const override { return s.clock.step % every_ == 0; }
  /// The diagnosis of an unphysical state (non-finite or too fast particles,
  /// particle pairs overlapping by more than half the smaller radius), or an
  /// empty string when the state is sound. Checkpoint writers call it so that
  /// they never replace a good checkpoint by a blown-up one.
  std::string diagnose(const sim::Scene& s) const;
  /// The newest checkpoint known good; the blow-up message points to it.
  void set_last_good_checkpoint(std::string path) { last_good_ = std::move(path); }

 private:
  std::string last_good_;
  double vmax_;
  double rayleigh_;
  std::int64_t every_;
};

}  // namespace grains::io
