#pragma once
// From a SceneConfig to a ready Scene and its step pipeline.
#include <memory>

#include "sim/laws/step_scale.hpp"
#include "sim/scene/scene_config.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {

/// What the scene needs, decided once from the config: which law slots,
/// which optional particle fields, which stages.
struct SceneNeeds {
  bool tangential = false, rolling = false, cohesion = false;
  /// The rolling and cohesion laws by registry name ("none" when the slot is off).
  std::string rolling_law = "none", cohesion_law = "none";
  int tangential_history = 0, rolling_history = 0;  // doubles per contact of each slot's law
  int normal_history = 0;  // the normal law's contact state (JKR: in contact), after the springs'
  bool rotation = false;
  bool ellipsoids = false;  // some particle is non-spherical: rigid-body integrator, shape dispatch
  bool clumps = false;      // some set is made of rigid clumps: body field, BodyStore and its stages
  bool gravity = false, walls = false, moving_walls = false;
  int history_size = 0;  // per contact (doubles of the neighbour list's history per entry, without PW85's)
  // ARKODE: the law's history is part of the ODE state; each contact keeps
  // [state | rate] (integrate/history_state_law.hpp), history_size is doubled.
  bool history_in_state = false;
  FieldSet fields;
};

SceneNeeds scene_needs(const SceneConfig& c, const PairTable& pairs);

/// Rayleigh time pi r sqrt(rho/G) / (0.1631 nu + 0.8766), the smallest over
/// the particle sets (smallest radius of each size distribution).
double rayleigh_time(const SceneConfig& c);

/// The lightest grain, the smallest radius of curvature and the Rayleigh
/// time over the particle sets and insertions: what a normal law's time
/// scale is computed from (sim/laws/step_scale.hpp).
GrainExtremes grain_extremes(const SceneConfig& c);

/// The particle records a case asks for: the counts of its particle sets
/// (clumps: their balls) and of every insertion it schedules (lattice sets
/// that fill their region without a count are left out). With `capped_only`,
/// only insertions capped by `times` count: an uncapped insertion places
/// what fits, which may be far less than its schedule.
std::int64_t planned_particles(const SceneConfig& c, bool capped_only = false);

/// Memory this machine has available now (MemAvailable of /proc/meminfo), in
/// bytes; 0 when unknown.
double available_memory();

/// Places the particles and sets the clock. Throws SetupError for problems
/// a user can fix (with the case-file location), e.g. an over-full region,
/// overlapping initial positions, a time step above the Rayleigh time, a
/// case whose grains' fields alone need more memory than the machine has.
/// Warnings (e.g. dt above 0.3 Rayleigh times) are appended to c.warnings.
Scene build_scene(SceneConfig& c);

/// Appends one grain of `set` at x: a sphere or an ellipsoid of bounding
/// radius r, or a clump of bounding radius r (a body with id body_id and its
/// balls), with orientation o and global ids from gid on (a clump takes one
/// per ball). `ellipsoid_fields`: the scene keeps semi-axes, orientations
/// and forms (it has ellipsoids). Throws SetupError naming `what` when the
/// grain (a clump's ball) lies outside the domain.
void add_grain(Scene& s, const ParticleSetConfig& set, const Vec3& x, double r, const Quat& o, std::int64_t& gid,
               std::int64_t body_id, bool ellipsoid_fields, const std::string& what);

/// Threads and ranks: the deterministic force sum when threads run, and under
/// MPI (or with periodic dimensions) the exchange, after which this rank
/// holds only the particles it owns. Called by build_scene. A case's
/// `deterministic: false` that threads override gets a warning in c.warnings.
void setup_parallel(Scene& s, SceneConfig& c, double rmax);

/// The physics stages the scene calls for, in phase order. Outputs are added
/// by the caller (io).
Pipeline assemble_pipeline(const Scene& s, const SceneConfig& c);

}  // namespace grains::sim
