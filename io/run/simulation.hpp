#pragma once
// A runnable simulation assembled from a case: the scene, the physics
// pipeline and the output stages the case asks for.
#include <filesystem>
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
};

/// Builds the scene and its physics pipeline (no outputs). Throws
/// sim::SetupError / CaseError with case-file locations.
Simulation make_simulation(Case c);

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

/// Adds the output stages, writes the initial frame (or restores
/// opt.restart), runs to the end time, writes summary.json into the output
/// folder and returns the summary. A signal (opt.handle_signals) ends the
/// run early with a checkpoint and summary.signal set.
RunSummary run(Simulation& sim, const RunOptions& opt);

class VtkOutput;
class CheckpointStage;

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
