#pragma once
// A runnable simulation assembled from a case: the scene, the physics
// pipeline and the output stages the case asks for.
#include <chrono>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>

#include "io/case/case.hpp"
#include "sim/scene/build_scene.hpp"

namespace grains::io {

struct Simulation {
  Case c;
  sim::Scene scene;
  sim::Pipeline pipeline;
  double rayleigh_time = 0;
  double build_seconds = 0;  // make_simulation: the scene (placement and its overlap check) and the pipeline
};

/// Builds the scene and its physics pipeline (no outputs). Throws
/// sim::SetupError / CaseError with case-file locations.
Simulation make_simulation(Case c);

/// `grains check`'s run-time estimate: runs the case's first steps (at most
/// `budget` seconds or 200 steps, without outputs; the simulation is left
/// advanced, so call it last) and scales their time to the whole run. A
/// line of text saying it is an estimate and what it rests on. Serial only
/// (under MPI the ranks' state is made by the run).
std::string estimate_run_time(Simulation& s, double budget = 1.0);

struct RunOptions {
  std::filesystem::path out_dir = "out";
  bool quiet = false;
  std::ostream* log = &std::cerr;
  /// Continue from this checkpoint instead of the case's initial state.
  std::filesystem::path restart;
  /// SIGINT/SIGTERM end the run after the current step with a checkpoint.
  bool handle_signals = false;
  /// Where a checkpoint goes when the output folder cannot take it
  /// (empty: $GRAINS_EMERGENCY_DIR, else <temp>/grains-emergency).
  std::filesystem::path emergency_dir;
};

struct RunSummary {
  std::int64_t steps = 0;
  double simulated_time = 0;
  double wall_seconds = 0;
  double particle_steps_per_second = 0;
  std::size_t particles_start = 0, particles_end = 0;
  std::int64_t lost_particles = 0;
  long neighbor_builds = 0;
  std::size_t frames = 0;
  int signal = 0;                  // the signal that interrupted the run, or 0
  std::string checkpoint;          // the last checkpoint written (or restarted from)
  std::string restarted_from;      // the checkpoint the run continued from
};

/// Thrown when an output fails (disk full, folder not writable); the message
/// says what failed and where the state was saved, if it could be.
struct OutputFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class VtkOutput;
class CheckpointStage;

/// A run taken in pieces (the Python module steps it in chunks): the
/// constructor adds the output stages and writes the initial frame (or
/// restores opt.restart); advance() steps; finish() ends it.
class Runner {
 public:
  Runner(Simulation& sim, const RunOptions& opt);
  Runner(const Runner&) = delete;
  Runner& operator=(const Runner&) = delete;
  ~Runner();

  /// Steps until the clock reaches `step` (past the case's end, the end moves
  /// there), a signal arrives (opt.handle_signals), or `stop` (if given,
  /// asked before each step) says so. A signal saves a checkpoint and ends
  /// the run. Returns the steps taken. An output failure saves the state
  /// where it fits and throws OutputFailure.
  std::int64_t advance(std::int64_t step, const std::function<bool()>& stop = {});
  /// Writes a checkpoint of the current step now; returns its file.
  std::filesystem::path checkpoint();
  /// The stages' finish() (unless a signal ended the run) and summary.json;
  /// once only.
  RunSummary finish();
  bool finished() const { return finished_; }
  int signal() const { return r_.signal; }
  CheckpointStage& checkpoints() { return *ck_; }

 private:
  /// An output failed: saves the state where it fits, throws OutputFailure saying where.
  [[noreturn]] void output_failed(const std::exception& e);
  Simulation& s_;
  RunOptions opt_;
  VtkOutput* vtk_ = nullptr;
  CheckpointStage* ck_ = nullptr;
  RunSummary r_;
  std::chrono::steady_clock::time_point t0_;
  double particle_steps_ = 0, pair_steps_ = 0, steps_run_ = 0;  // summed over steps: owned particles, list entries
  bool finished_ = false;
};

/// Adds the output stages, writes the initial frame (or restores
/// opt.restart), runs to the end time, writes summary.json into the output
/// folder and returns the summary. A signal (opt.handle_signals) ends the
/// run early with a checkpoint and summary.signal set.
RunSummary run(Simulation& sim, const RunOptions& opt);

/// The output stages the run itself talks to.
struct OutputStages {
  VtkOutput* vtk = nullptr;  // null without VTK output
  CheckpointStage* checkpoints = nullptr;
};

/// Adds output stages (blow-up check, VTK, progress, checkpoints) as `run` does.
OutputStages add_output_stages(Simulation& sim, const RunOptions& opt);

/// Text for `grains check`: the stages in order and the per-particle fields.
std::string describe(const Simulation& sim);

}  // namespace grains::io
