#pragma once
// Solid-fraction field output: at its cadence, the coarse-grained solid
// fraction of the packing on a regular grid (contact/correlation/
// solid_fraction.hpp: NUFFT of the ball centres times the ball transform and
// a Gaussian of width `smoothing`), written as VTK image data
// (frames/solid_fraction_NNNNNN.vti) with a solid_fraction.pvd series.
//
// Shapes: spheres and clump member balls as they are (overlapping balls of
// one clump count their shared volume twice: the field is the sum of ball
// indicators, said in the file's field data); an ellipsoid as the sphere of
// equal volume at its centre (exact for the mean over regions much larger
// than the particle; the field's detail below the particle size is then
// approximate).
// Case-file keys: output.solid_fraction (grains docs output.solid_fraction).
#include <filesystem>
#include <vector>

#include "sim/scene/stage.hpp"

namespace grains::io {

struct SolidFractionConfig {
  bool enabled = false;
  double spacing = 0;      // grid spacing, m
  double smoothing = -1;   // Gaussian width, m (< 0: the spacing)
  double tolerance = 1e-4;
  std::int64_t every_steps = 0;  // 0: at the VTK frame cadence
  double every = 0;              // s (converted to steps at set-up)
};

class SolidFractionOutput final : public sim::Stage {
 public:
  SolidFractionOutput(std::filesystem::path dir, SolidFractionConfig cfg, std::int64_t every_steps);
  std::string name() const override;
  sim::Phase phase() const override { return sim::Phase::Output; }
  void run(sim::Scene& s) override;
  bool reads_state(const sim::Scene& s) const override { return every_ > 0 && s.clock.step % every_ == 0; }
  void finish(sim::Scene& s) override;
  /// The field of the initial state (a restart continues the series as it is).
  void start(sim::Scene& s) override { write_frame(s); }
  /// Computes the field of the scene now (values at the nodes, x fastest),
  /// with the grid it used (origin, spacing, dims).
  std::vector<double> field(const sim::Scene& s, std::array<double, 3>& origin, std::array<int, 3>& dims) const;
  void write_frame(const sim::Scene& s);
  void write_file(const sim::Scene& s, const std::vector<double>& values, const std::array<double, 3>& origin,
                  const std::array<int, 3>& dims);

 private:
  std::filesystem::path dir_;
  SolidFractionConfig cfg_;
  std::int64_t every_;
  std::int64_t last_step_ = -1;
  std::vector<double> times_;
};

}  // namespace grains::io
