#pragma once
// Stress and flow measurement (output.stress): at its cadence and at the
// last step, the stress
// tensor of a region (by default the box the walls and periodic dimensions
// bound), contact and kinetic parts, its solid fraction and mean velocity,
// in OUTDIR/stress.csv; with a profile, the same per bin along an axis in
// OUTDIR/profile.csv. At the end, the means over the rows from average_after
// on (read back from the files, so a restarted run's means cover the whole
// run): summary.json and OUTDIR/profile_mean.csv.
//
// Contact part: Love–Weber (sim/state/stress_probe.hpp), gathered by the
// force stages on the measured step only. Kinetic part: sum m (v - u)(v - u)
// / V by centre, u the mass-weighted mean velocity of the grain's bin (of the
// region without a profile). Solid fraction: per bin, the exact volume of
// each sphere inside the slab (an ellipsoid as its equal-volume sphere); of
// the region, the grains whose centre is in it. Compressive stress > 0.
// Summed over the ranks. Verlet only; not with clumps.
// Case-file keys: output.stress (grains docs output.stress).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sim/scene/stage.hpp"

namespace grains::io {

struct StressConfig {
  bool enabled = false;
  std::int64_t every_steps = 0;  // 0: at the VTK frame cadence
  double every = 0;              // s
  double average_after = 0;      // s
  bool region_given = false;
  sim::Vec3 lo{0, 0, 0}, hi{0, 0, 0};
  int axis = -1;  // profile axis (-1: no profile)
  int bins = 0;
  std::string where;
};

/// The region a stress measurement covers when none is given: along each
/// axis the periodic domain, else the gap between the infinite planes facing
/// each other across it, else the domain.
void box_region(const sim::Scene& s, sim::Vec3& lo, sim::Vec3& hi);

class StressOutput final : public sim::Stage {
 public:
  StressOutput(std::filesystem::path dir, StressConfig cfg, std::int64_t every_steps);
  std::string name() const override;
  sim::Phase phase() const override { return sim::Phase::Output; }
  void start(sim::Scene& s) override;
  void restart(sim::Scene& s, const sim::RestartPoint&) override;
  void run(sim::Scene& s) override;
  bool reads_state(const sim::Scene& s) const override { return s.stress_probe == &probe_; }  // it measures
  void finish(sim::Scene& s) override;
  std::string summary_json() const override;

 private:
  void arm(sim::Scene& s);
  void measure(sim::Scene& s);
  void open(bool restarting, std::int64_t step);
  std::filesystem::path dir_;
  StressConfig cfg_;
  std::int64_t every_;
  sim::StressProbe probe_;
  std::ofstream stress_, profile_;
  std::string summary_;
};

}  // namespace grains::io
