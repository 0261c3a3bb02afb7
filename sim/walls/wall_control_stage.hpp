#pragma once
// The stage that drives walls with a controlled motion (wall_control.hpp):
// after the force phase (the kick phase, so the checkpoint of a step holds
// the speeds its next step moves with), it sums each controlled wall's load
// over the ranks, measures the sample's cross-section or length from the box,
// and sets the wall's speed for the next step. Present only in scenes with
// such walls.
#include <string>
#include <vector>

#include "sim/scene/stage.hpp"

namespace grains::sim {

class ControlWalls final : public Stage {
 public:
  std::string name() const override { return "walls.control"; }
  Phase phase() const override { return Phase::Kick; }
  void run(Scene& s) override;

 private:
  std::vector<double> sums_;  // the controlled walls' loads, summed over the ranks (kept: no allocation per step)
};

/// The cross-section of the box normal to the axis direction d: along each
/// other axis, the periodic length or the gap between the infinite planes
/// facing each other across it; or a cylinder's disc when one with its axis
/// along d holds the grains. 0, with `why` set, when the box has no such bound.
double box_cross_section(const Scene& s, const Vec3& d, std::string* why);
/// The sample's length along d from the plane at `point`: the distance to the
/// nearest infinite plane facing it (normal -d). 0, with `why` set, when none.
double box_length(const Scene& s, const Vec3& point, const Vec3& d, std::string* why);
/// Set-up of the controlled walls: checks against the scene's box (a located
/// error when the cross-section or the length cannot be found, or with
/// ARKODE), the loads measured from now on, a strain rate's first speed.
void setup_wall_controls(Scene& s, bool arkode, const std::string& integrator_where);

}  // namespace grains::sim
