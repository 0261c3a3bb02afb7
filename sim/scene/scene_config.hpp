#pragma once
// A validated, unit-explicit description of a scene: what io::Case hands to
// sim. Every value here is in SI units and already range-checked; `where`
// strings (file:line:column) let set-up errors point back at the case file.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/integrate/radius_growth.hpp"
#include "sim/laws/material.hpp"
#include "sim/scene/scene.hpp"
#include "sim/walls/walls.hpp"

namespace grains::sim {

/// Thrown for a problem a user can fix in the case file (or its inputs).
struct SetupError : std::runtime_error {
  using std::runtime_error::runtime_error;
};


struct SizeDistribution {
  enum class Kind { Fixed, Uniform, Normal, LogNormal, Discrete } kind = Kind::Fixed;
  double radius = 0;             // Fixed
  double min = 0, max = 0;       // Uniform; truncation bounds for Normal/LogNormal
  double mean = 0, stddev = 0;   // Normal/LogNormal (of the radius itself)
  std::vector<double> values, weights;  // Discrete
  double smallest() const;
  double largest() const;
};

struct Region {
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};
};

struct Placement {
  enum class Kind { RandomFill, Lattice, File } kind = Kind::RandomFill;
  Region region;
  double spacing = 0;  // Lattice; 0 = largest diameter
  std::uint64_t seed = 1;
  std::vector<Vec3> positions;   // File
  std::vector<double> radii;     // File (optional 4th column)
  std::string positions_path;               // File: the file, for messages
  std::vector<std::int64_t> position_line;  // File: its line of each position (1-based)
  /// "file:line" of position k of a File placement (for messages).
  std::string where(std::size_t k) const { return positions_path + ":" + std::to_string(position_line[k]); }
};

/// The shape of a particle set. Ellipsoid semi-axes scale with each
/// particle's size: axes = bounding radius * axes_rel, where the bounding
/// radius is the set's radius (from its size distribution) times
/// bounding_factor. With `aspect_ratio: alpha` the radius is the volume-
/// equivalent radius and the axes are r (alpha^{2/3}, alpha^{-1/3}, alpha^{-1/3})
/// (prolate along the body x axis for alpha > 1, oblate for alpha < 1).
/// A clump shape for a particle set, normalised to a bounding radius of 1:
/// the balls in the principal body frame about the centre of mass, and the
/// mass properties of the union of the balls per unit density (from
/// contact/clump's ClumpTemplate). A clump of bounding radius s has balls
/// s c_k, s r_k, volume s^3 volume, principal inertia rho s^5 inertia.
struct ClumpShape {
  std::vector<Vec3> centres;   // body frame, |c| + r <= 1
  std::vector<double> radii;
  double volume = 0;           // of the union of balls
  Vec3 inertia{0, 0, 0};       // principal moments per unit density, ascending
  std::string source;          // clump file or mesh (for messages)
};

struct ShapeConfig {
  enum class Kind { Sphere, Ellipsoid, Clump } kind = Kind::Sphere;
  std::shared_ptr<const ClumpShape> clump;  // Kind::Clump
  Vec3 axes_rel{1, 1, 1};      // semi-axes / bounding radius (largest entry 1)
  double bounding_factor = 1;  // bounding radius / size-distribution radius
  bool random_orientation = true;
  Quat orientation = Quat::Identity();
};

struct ParticleSetConfig {
  std::string name;
  ShapeConfig shape;
  int material = 0;
  SizeDistribution size;
  std::int64_t count = 0;  // 0 with Lattice: fill the region
  Placement placement;
  Vec3 velocity{0, 0, 0};
  /// Held: never integrated, the grains keep `velocity` (zero: fixed in
  /// place; else they move rigidly at it) and exert forces as walls do
  /// (m* of a contact with one is the other grain's mass).
  bool frozen = false;
  std::string where;
};

/// Insertion of new grains during a run (case file: insert[]; sim/insert/).
/// The grains are described as a particle set (shape, material, size,
/// velocity); `grains.count` is the number asked for at each insertion.
struct InsertionConfig {
  enum class Method { Fft, Random } method = Method::Fft;
  ParticleSetConfig grains;
  Region region;              // holds the whole inserted grains
  double at = 0;              // time of the first insertion (s); 0: after the first step
  double every = 0;           // s between insertions; 0: once
  double until = 0;           // no insertion after this time (s); 0: the end of the run
  std::int64_t times = 0;     // insertions at most; 0: no limit
  int orientations = 8;       // trial orientations per field (non-spherical grains with random orientation)
  double spacing = 0;         // fft grid spacing (m); 0: a quarter of the grain's largest ball
  double margin = 0.25;       // fft: shape balls inflated by margin x the largest ball's radius
  double mode_factor = 1;     // fft: modes per axis / grid nodes per axis
  std::int64_t attempts = 100000;  // random: consecutive failed trials before giving up
  double budget = 0;          // wall-clock seconds per insertion; 0: none
  std::uint64_t seed = 1;
  std::string where;          // file:line:column of the entry
};

enum class SlotChoice { Auto, None, On };

/// The time integrator (case file: time.integrator).
enum class Integrator {
  Verlet,  // velocity Verlet, fixed step dt
  Arkode,  // SUNDIALS ARKODE explicit adaptive Runge-Kutta (sim/integrate/arkode.hpp); dt is the largest step
};

/// Options of the ARKODE integrator (case file: time.rtol, time.atol, time.order).
struct ArkodeConfig {
  double rtol = 1e-6;  // relative tolerance
  double atol = 1e-6;  // absolute tolerance in the scene's units (smallest radius, scene speed)
  int order = 4;       // order of the embedded ERK pair (2..8; ARKODE's default tables)
};

/// Threads and MPI ranks (`parallel:` in the case file).
struct ParallelConfig {
  /// Ordered force sums (results independent of thread and rank counts, and
  /// continuations of checkpoints bitwise on the same rank count). Unset:
  /// on under MPI with more than one rank, off in a serial run; always on
  /// with more than one thread.
  std::optional<bool> deterministic;
  std::array<int, 3> dims{0, 0, 0};  // rank grid; 0 = chosen from the domain shape
  double balance_threshold = 1.1;    // rebalance when max/mean estimated work per rank exceeds it
  std::string where;                 // case-file location, for messages
};

struct SceneConfig {
  Domain domain;
  /// Lees–Edwards (domain.shear): the grains start on the mean flow; where it is written.
  bool shear_profile = true;
  std::string shear_where;
  Vec3 gravity{0, 0, 0};
  std::vector<Material> materials;
  std::vector<PairOverride> overrides;
  std::vector<ParticleSetConfig> sets;
  Walls walls;
  NormalLawChoice normal;  // contact.model and its keys (sim/laws/normal_laws.hpp)
  std::string normal_where;  // file:line:column of contact.model
  SlotChoice tangential = SlotChoice::Auto, rolling = SlotChoice::Auto, cohesion = SlotChoice::Auto;
  /// The law named for the rolling and cohesion slots when On (contact.rolling,
  /// contact.cohesion: a name from their registries, sim/laws/contact_law.hpp);
  /// empty: the slot's first law after "none".
  std::string rolling_law, cohesion_law;
  double dt = 0;           // absolute time step, or 0
  double dt_rayleigh = 0;  // fraction of the Rayleigh time, or 0
  std::string dt_where;
  double end_time = 0;
  Integrator integrator = Integrator::Verlet;
  ArkodeConfig arkode;
  std::string integrator_where;  // file:line:column of time.integrator
  double skin = 0.1;       // neighbour skin as a fraction of the largest diameter
  bool skin_per_grain = false;  // each grain's skin is `skin` times its own diameter
  bool sort_particles = true;
  ParallelConfig parallel;
  double overlap_tolerance = 0.01;  // initial overlaps above this fraction of the smaller radius are refused
  RadiusGrowthConfig growth;        // isotropic compression by growing radii (radius_growth)
  std::string growth_where;
  std::vector<InsertionConfig> insertions;  // insert[]: grains added during the run
  std::vector<std::string> warnings;  // filled by build_scene

  /// Some particle set is frozen (particles[].frozen).
  bool has_frozen() const {
    for (const auto& set : sets)
      if (set.frozen) return true;
    return false;
  }
  /// The fastest speed grains are given at insertion (0 without insertions):
  /// part of the scene's speed scale (blow-up check, ARKODE's scales).
  double fastest_insertion() const {
    double v = 0;
    for (const auto& in : insertions) v = std::max(v, in.grains.velocity.norm());
    return v;
  }
};

}  // namespace grains::sim
