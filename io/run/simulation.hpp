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
};

/// Adds the output stages, writes the initial frame, runs to the end time,
/// writes summary.json into the output folder and returns the summary.
RunSummary run(Simulation& sim, const RunOptions& opt);

/// Adds output stages (VTK, progress, blow-up check) as `run` does.
void add_output_stages(Simulation& sim, const RunOptions& opt);

/// Text for `grains check`: the stages in order and the per-particle fields.
std::string describe(const Simulation& sim);

}  // namespace grains::io
