#pragma once
// The pressure-imposed Lees–Edwards cell (domain.shear.pressure; da Cruz et
// al. 2005): the cell's height L_g along the gradient follows a servo that
// holds the normal stress across it, sigma_gg, at the target P*. After each
// step's forces (the kick phase) it measures sigma_gg of the whole cell
// (Love–Weber contact part from a probe armed every step, plus the kinetic
// part about the mean gradient velocity), summed over the ranks, and dilates
// the cell at
//
//   (dL_g/dt) / L_g = gain |rate| (sigma_gg - P*) / P*,  clamped to +-max_dilation,
//
// scaling every grain's coordinate along the gradient affinely about the
// cell's lower face (velocities are kept). The relative pressure error thus
// relaxes over a strain of 1/(gain K/P*), K the cell's bulk stiffness: fast
// in a dense flow, a few strain units in a dilute one; the loop is stable
// while gain |rate| dt K/P* < 2 (the default gain 0.1 leaves a wide margin
// for K/P* up to 1e5 at the time steps DEM uses). Present only when the case
// asks for a pressure.
#include <string>
#include <vector>

#include "sim/scene/stage.hpp"

namespace grains::sim {

class ShearPressure final : public Stage {
 public:
  std::string name() const override { return "shear.pressure"; }
  Phase phase() const override { return Phase::Kick; }
  void start(Scene& s) override { arm(s); }
  void restart(Scene& s, const RestartPoint&) override { arm(s); }
  void run(Scene& s) override;
  void finish(Scene& s) override;
  std::string summary_json() const override;

 private:
  void arm(Scene& s);
  StressProbe probe_;
  std::vector<double> sums_;  // kept: no allocation per step
  double sigma_ = 0;          // sigma_gg measured last, Pa
  double dilation_ = 0;       // (dL_g/dt) / L_g set last, 1/s
  double height_ = 0;         // L_g, m
  double min_height_ = 0, max_height_ = 0;
};

/// Set-up checks of the pressure servo: a cell with a cross-section normal
/// to the gradient (a located error otherwise).
void setup_shear_pressure(const Scene& s, const std::string& where);

}  // namespace grains::sim
