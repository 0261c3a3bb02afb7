#pragma once
// Wall loads: at its cadence, one CSV row per wall (OUTDIR/wall_loads.csv)
// with the force the particles exert on it and the torque about its load
// point (a mesh wall's torque_point, by default on its rotation axis; another
// kind's position), and for a rotating mesh wall the torque about its axis
// (what drives a drum or a mixer shaft). summary.json gets each wall's mean
// over the rows at or after `average_after` and its last row. Summed over
// ranks; the forces are those of the step's force evaluation.
// Case-file keys: output.wall_loads (grains docs output.wall_loads).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

#include "sim/scene/stage.hpp"

namespace grains::io {

struct WallLoadConfig {
  bool enabled = false;
  std::int64_t every_steps = 0;  // 0: at the VTK frame cadence
  double every = 0;              // s
  double average_after = 0;      // s: the summary's mean starts here
};

class WallLoadOutput final : public sim::Stage {
 public:
  WallLoadOutput(std::filesystem::path dir, WallLoadConfig cfg, std::int64_t every_steps);
  std::string name() const override;
  sim::Phase phase() const override { return sim::Phase::Output; }
  void start(sim::Scene& s) override;
  void restart(sim::Scene& s, const sim::RestartPoint&) override;
  void run(sim::Scene& s) override;
  bool reads_state(const sim::Scene& s) const override { return every_ > 0 && s.clock.step % every_ == 0; }
  void finish(sim::Scene& s) override;
  std::string summary_json() const override;

 private:
  void prepare(sim::Scene& s);
  void write_rows(const sim::Scene& s);
  std::filesystem::path file_;
  WallLoadConfig cfg_;
  std::int64_t every_;
  std::int64_t last_step_ = -1;
  std::ofstream out_;
  struct Sum {
    std::string name, kind;
    double force[3] = {0, 0, 0}, torque[3] = {0, 0, 0}, axial = 0;
    double last_force[3] = {0, 0, 0}, last_torque[3] = {0, 0, 0}, last_axial = 0;
    bool has_axis = false;
    std::int64_t rows = 0;
  };
  std::vector<Sum> sums_;
};

}  // namespace grains::io
