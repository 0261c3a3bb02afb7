#pragma once
// A wall's controlled motion along a direction (walls[].control): a servo
// that holds a target normal stress or force, or a prescribed strain rate.
// Any wall kind takes it (planes and meshes; a plane moves along its normal).
//
// The servo (stress or force), once per step after the force phase, from the
// load F the grains put on the wall along -d (d: the direction of motion
// towards the grains) and the sums K and C of its contacts' normal
// stiffnesses and dashpots:
//   F* = stress * A (A: the cross-section, given or from the box) or force
//   v  = gain (F* - F) / (K dt + C),  clamped to [-max_speed, max_speed]
// K dt + C is how much the load changes, within one step, per unit speed of
// the wall (the springs compress by v dt, the dashpots see v): were the wall's
// contacts all that responds, the error would shrink by the fraction `gain`
// per step; the grains behind them giving way, it shrinks less. (Without C the
// dashpots, which dominate at a step of a fraction of the contact time, make
// the wall chatter between +-max_speed.) A wall touching nothing moves
// towards the grains at max_speed. The speed is the wall's velocity for the
// next step (at rest before the first).
//
// Strain rate: v = rate * L, L the sample's current length along d (the
// distance to the facing plane); rate > 0 compresses.
//
// The wall sets its own velocity: `velocity` cannot be given with it.
#include <algorithm>
#include <cmath>

#include "contact/contact_geometry.hpp"

namespace grains::sim {

struct WallControl {
  enum class Mode { None, Stress, Force, StrainRate };
  Mode mode = Mode::None;
  double target = 0;     // Pa, N or 1/s by mode (stress and force: > 0, compressive)
  double area = 0;       // m^2; 0: the box's cross-section, found each step (stress)
  double max_speed = 0;  // m/s (servo; strain rate: the speed's bound, raised as it grows)
  double gain = 0.5;     // fraction of the error the wall's contact springs take out per step
  contact::Vec3 direction{0, 0, 1};  // unit, towards the grains
  std::string where;     // the control block in the case file

  // State (checkpointed): the speed along direction for the next step, the
  // distance travelled along it so far.
  double speed = 0;
  double travel = 0;
  // The last measurement (output): the load along -direction, its target, the
  // cross-section and the contacts' stiffness sum.
  double load = 0, target_load = 0, area_now = 0, stiffness = 0, damping = 0;

  bool active() const { return mode != Mode::None; }
  bool servo() const { return mode == Mode::Stress || mode == Mode::Force; }

  /// The servo's speed from the load F, its target F*, the sums K and C of
  /// the contacts' stiffnesses and dashpots, and the step dt.
  double servo_speed(double F, double F_target, double K, double C, double dt) const {
    const double e = F_target - F;
    const double response = K * dt + C;
    if (!(response > 0)) return e > 0 ? max_speed : e < 0 ? -max_speed : 0.0;
    return std::clamp(gain * e / response, -max_speed, max_speed);
  }
};

}  // namespace grains::sim
