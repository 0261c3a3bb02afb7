#pragma once
// SUNDIALS ARKODE as a DEM integrator: an explicit adaptive Runge-Kutta
// method (ERKStep) with error control, on the same force code as velocity
// Verlet. The design and its measured behaviour are in docs/integrators.md;
// in short:
//
//  * The ODE state y holds, per free particle, the displacement since the
//    last neighbour build and the velocity; spheres that rotate add omega,
//    scenes with ellipsoids add the orientation quaternion and the angular
//    momentum; rigid clumps contribute their body's centre, velocity,
//    quaternion and angular momentum (their balls follow the body).
//  * The right-hand side is the pipeline's force phase, run at each trial
//    state (ClearForces, the contact stages, the clump sums): nothing of the
//    force code is duplicated.
//  * Contact history is part of y too: the tangential spring and the rolling
//    torque of every neighbour-list entry and every particle-wall slot. The
//    contact stages run with HistoryInState<Law> (history_state_law.hpp):
//    the law computes the force of the trial state's spring and its rate
//    (the tangential relative velocity; -k_r w_r), so ARKODE integrates the
//    springs with the same order and error control as the motion. Trial
//    stages and rejected steps leave nothing behind: the history buffers are
//    written from y before every evaluation.
//  * After each accepted step the forces are evaluated once more at the new
//    state; that evaluation projects every spring onto its tangent plane and
//    the Coulomb (rolling) limit and zeroes the springs of pairs that came
//    apart, and the projected springs are written back into y. The
//    quaternions are renormalised (a projection onto |q| = 1) in the same
//    place, and ARKODE is reset to the projected state: each step starts
//    from a consistent state; ARKODE keeps its step-size history.
//  * Local errors are measured in the max norm over the components (not
//    ARKODE's default RMS), so a collision among thousands of resting
//    particles is not averaged away: every particle meets the tolerance.
//  * The neighbour list is checked between steps, with a look-ahead: a step
//    may not start unless twice the largest speed over the coming stretch
//    keeps every particle within the skin; otherwise the list is rebuilt
//    first (or the stretch shortened). After a rebuild (particles re-sorted,
//    some may have left the domain) y is packed again.
//  * The case's dt is the largest step ARKODE may take and the cadence of
//    the clock (outputs, step counter): each pipeline step integrates
//    exactly from clock.time to clock.time + dt with as many adaptive steps
//    as the tolerances need; the forces in the particle store are those of
//    the end state (for the outputs).
//
// Serial, or OpenMP threads (the SUNDIALS OpenMP vector when more than one
// thread is available). Under MPI with more than one rank it refuses to run.
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "sim/scene/scene_config.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {

/// ARKODE could not continue (the local error test kept failing down to the
/// smallest step, or the right-hand side stayed non-finite): the state has
/// blown up or the force is discontinuous beyond repair.
struct IntegrationFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Which degrees of freedom the ODE state carries.
struct ArkodeLayout {
  bool rotation = false;  // free spheres carry omega (dw/dt = T/I)
  bool rigid = false;     // free particles carry a quaternion and the angular momentum (scenes with ellipsoids)
  bool clumps = false;    // the rigid clumps of Scene::bodies
  // The law's history per contact (HistoryInState: [state | rate] of this
  // size each in the buffers), and whether a PW85 warm start follows it.
  int tangential_history = 0;  // spring, m
  int rolling_history = 0;     // rolling torque, N m
  bool pw85_slot = false;
};

struct ArkodeStats {
  long steps = 0;                // accepted steps
  long error_test_failures = 0;  // rejected steps
  long rhs_evaluations = 0;         // force phase at a trial state
  long projection_evaluations = 0;  // force phase at an accepted step's end, projecting the springs
  long end_evaluations = 0;         // force phase at the end of a clock step, for the outputs (no springs)
  long repacks = 0;              // state packed again after a neighbour rebuild
  long lookahead_rebuilds = 0;   // rebuilds forced by the look-ahead (not by the plain skin trigger)
  double min_step = 0, max_step = 0;  // s, over accepted steps
};

/// The driver stage (Phase::Drift, Stage::is_driver()).
class ArkodeIntegrator : public Stage {
 public:
  virtual const ArkodeStats& stats() const = 0;
  /// Called after every accepted step with the scene at the step's end
  /// (particles, bodies, walls; clock.time is the step's end time), for
  /// diagnostics that need more than the clock's samples (tests, the report).
  using StepObserver = std::function<void(const Scene&)>;
  void set_step_observer(StepObserver f) { observer_ = std::move(f); }

 protected:
  StepObserver observer_;
};

/// Scales of the absolute tolerance: positions atol * length, velocities
/// atol * speed, angular velocities atol * speed / length, quaternions atol,
/// angular momenta atol * I * speed / length (I the largest principal moment
/// of each body), tangential springs atol * length, rolling torques
/// atol * mass * speed^2.
struct ArkodeScales {
  double length = 1;  // smallest particle radius, m
  double speed = 1;   // the scene's speed: fastest initial speed + free fall through the domain + fastest wall, m/s
  double mass = 1;    // smallest particle mass, kg (rolling torques: atol * mass * speed^2)
};

/// True when this build has SUNDIALS (GRAINS_WITH_SUNDIALS).
bool arkode_available();

/// The driver. Throws SetupError (naming `where`, the case file's
/// time.integrator) when this build has no SUNDIALS or when MPI is
/// initialised with more than one rank.
std::unique_ptr<ArkodeIntegrator> make_arkode_integrator(const ArkodeConfig& c, const ArkodeLayout& layout,
                                                         const ArkodeScales& scales, const std::string& where);

}  // namespace grains::sim
