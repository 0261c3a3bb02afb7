#pragma once
// A case file: YAML in, a validated sim::SceneConfig and output settings out.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "io/case/validator.hpp"
#include "io/output/mass_output.hpp"
#include "io/output/solid_fraction_output.hpp"
#include "io/output/stress_output.hpp"
#include "io/output/wall_load_output.hpp"
#include "sim/scene/scene_config.hpp"

namespace grains::io {

struct OutputConfig {
  double every = 0;            // simulated seconds between frames (0: use every_steps)
  std::int64_t every_steps = 0;  // steps between frames (0 and every = 0: first and last only)
  bool vtk = true;
  bool progress = true;
  double progress_interval = 2.0;  // wall-clock seconds between progress lines
  SolidFractionConfig solid_fraction;
  MassOutputConfig mass;
  WallLoadConfig wall_loads;
  StressConfig stress;
};

/// Periodic HDF5 checkpoints (io/checkpoint): cadence and retention.
struct CheckpointConfig {
  double every = 0;              // simulated seconds between checkpoints (0: use every_steps)
  std::int64_t every_steps = 0;  // steps between checkpoints (0 and every = 0: only on signals and at the end)
  int keep = 3;                  // newest checkpoints kept in OUTDIR/checkpoints
};

struct Case {
  std::string path;      // the case file (or a name for in-memory text)
  std::string base_dir;  // folder relative paths are resolved against
  std::string text;      // the case file as read (kept for checkpoints)
  YAML::Node root;       // after --set overrides
  sim::SceneConfig scene;
  OutputConfig output;
  CheckpointConfig checkpoint;
  double read_seconds = 0;  // spent reading and checking it (a positions file included)
};

/// Reads and validates a case file; `overrides` are "key.path=value" strings
/// (list entries by index: materials.0.friction=0.3). Throws CaseError with
/// every problem found, each as file:line:column: what is wrong, what is valid.
Case load_case(const std::string& path, const std::vector<std::string>& overrides = {});
/// The same from text in memory; `name` stands for the file in messages.
Case parse_case(const std::string& text, const std::string& name, const std::vector<std::string>& overrides = {},
                const std::string& base_dir = ".");

/// Registers the io sections (output) with the effect documentation.
void register_io_docs();

}  // namespace grains::io
