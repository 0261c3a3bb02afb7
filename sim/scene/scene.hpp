#pragma once
// The state of a run: particles, walls, materials, neighbour lists, clock.
#include <array>
#include <cmath>
#include <memory>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/laws/material.hpp"
#include "sim/neighbor/neighbor_list.hpp"
#include "sim/state/body_store.hpp"
#include "sim/state/particle_store.hpp"
#include "sim/state/stress_probe.hpp"
#include "sim/walls/walls.hpp"

namespace grains::sim {

class Exchange;

struct Domain {
  Vec3 lo{0, 0, 0};
  Vec3 hi{1, 1, 1};
  /// Periodic dimensions: a particle leaving through one face comes back
  /// through the opposite one (ghost images, sim/parallel/exchange.hpp).
  std::array<bool, 3> periodic{false, false, false};
  bool any_periodic() const { return periodic[0] || periodic[1] || periodic[2]; }
  /// Inside in every non-periodic dimension.
  bool contains(const Vec3& x) const {
    for (int d = 0; d < 3; ++d)
      if (!periodic[d] && !(x[d] >= lo[d] && x[d] <= hi[d])) return false;
    return true;
  }
  /// Brings x into [lo, hi) along the periodic dimensions; returns the shift applied.
  Vec3 wrap(Vec3& x) const {
    Vec3 s = Vec3::Zero();
    for (int d = 0; d < 3; ++d) {
      if (!periodic[d]) continue;
      const double L = hi[d] - lo[d];
      if (x[d] < lo[d] || x[d] >= hi[d]) s[d] = -L * std::floor((x[d] - lo[d]) / L);
    }
    x += s;
    return s;
  }

  /// Lees–Edwards boundaries (domain.shear): steady simple shear at `rate`,
  /// the mean flow along `flow` growing along `gradient`, both periodic. The
  /// image of the cell across the gradient's upper face is displaced along
  /// the flow by offset(t) = rate L_g t and moves at speed() = rate L_g
  /// relative to it; a grain leaving through that face comes back through
  /// the lower one displaced by -offset and slowed by speed(), and the other
  /// way round. With `pressure` > 0 the cell's height L_g follows a servo
  /// (sim/scene/shear_pressure_stage.hpp); the offset is then integrated
  /// piecewise: base_offset at base_time, growing at rate L_g since.
  struct Shear {
    int flow = -1, gradient = -1;
    double rate = 0;  // 1/s
    double pressure = 0;        // the imposed normal stress across the gradient, Pa (0: the volume is fixed)
    double gain = 0.1;          // the servo's relative dilation rate per relative pressure error, per unit |rate|
    double max_dilation = 0;    // the fastest |dL_g/dt| / L_g, 1/s (0: |rate|)
    double base_offset = 0, base_time = 0;  // the offset (not wrapped) at base_time (0, 0 at a fixed volume)
    bool on() const { return flow >= 0; }
    bool servo() const { return on() && pressure > 0; }
  } shear;
  double shear_speed() const {
    return shear.on() ? shear.rate * (hi[shear.gradient] - lo[shear.gradient]) : 0.0;
  }
  /// The upper image's displacement along the flow at time t, not wrapped.
  double shear_travel(double t) const { return shear.base_offset + shear_speed() * (t - shear.base_time); }
  /// The upper image's displacement along the flow at time t, in [0, L_flow).
  double shear_offset(double t) const {
    const double L = hi[shear.flow] - lo[shear.flow];
    const double d = std::fmod(shear_travel(t), L);
    return d < 0 ? d + L : d;
  }
  /// A new cell height along the gradient (the pressure servo), from time t
  /// on: the offset stays continuous and grows at the new speed.
  void set_gradient_length(double L, double t) {
    shear.base_offset = shear_travel(t);
    shear.base_time = t;
    hi[shear.gradient] = lo[shear.gradient] + L;
  }
  /// A separation d = a - b of two points, to its nearest periodic image
  /// along each periodic axis (Lees–Edwards: an image across the gradient's
  /// faces is also displaced along the flow by the offset at time t).
  Vec3 nearest_image(Vec3 d, double t) const {
    if (shear.on()) {
      const int g = shear.gradient, f = shear.flow;
      const double k = std::round(d[g] / (hi[g] - lo[g]));
      if (k != 0) {
        d[g] -= k * (hi[g] - lo[g]);
        d[f] -= k * shear_offset(t);
      }
    }
    for (int a = 0; a < 3; ++a)
      if (periodic[a]) {
        const double L = hi[a] - lo[a];
        d[a] -= L * std::round(d[a] / L);
      }
    return d;
  }
  /// wrap() for a grain with velocity v at time t: across the sheared face
  /// first (its position along the flow and its velocity change), then along
  /// every periodic dimension.
  void wrap(Vec3& x, Vec3& v, double t) const {
    if (shear.on()) {
      const int g = shear.gradient, f = shear.flow;
      const double L = hi[g] - lo[g];
      const double k = std::floor((x[g] - lo[g]) / L);  // faces crossed upwards (usually -1, 0, 1)
      if (k != 0) {
        x[g] -= k * L;
        x[f] -= k * shear_offset(t);
        v[f] -= k * shear_speed();
      }
    }
    wrap(x);
  }
};

struct Clock {
  double time = 0;      // simulated time, s
  double dt = 0;        // time step, s
  double end_time = 0;  // s
  std::int64_t step = 0;
  std::int64_t n_steps = 0;  // total steps of the run
};

/// The radius-growth servo between steps (integrate/radius_growth.hpp): what
/// it measured last and the rate in force. Part of the state a checkpoint
/// saves, so that a restarted compression continues bitwise.
struct GrowthServo {
  bool started = false;            // the first growth step has run
  bool capped = false;             // growth stopped at max_scale
  std::int64_t last_measure = -1;  // step of the last measurement (-1: measure now)
  double overlap = 0;              // overlap per particle measured then
  double rate = 0;                 // growth rate in force, 1/s
  double phase_rate = 0;           // rate and target of the schedule phase in force
  double phase_target = 0;
};

/// Force and torque a wall takes from the particles (torque about its load
/// point: a mesh wall's torque_point, else its position).
struct WallLoad {
  Vec3 force{0, 0, 0};
  Vec3 torque{0, 0, 0};
  double stiffness = 0;  // the sum of its contacts' normal stiffnesses and dashpots (a servo's gain)
  double damping = 0;
};

struct Scene {
  Domain domain;
  ParticleStore particles;
  BodyStore bodies;  // rigid clumps; empty unless the scene has clumps
  Walls walls;
  std::vector<Material> materials;
  PairTable pairs;
  NeighborList neighbors;
  Vec3 gravity{0, 0, 0};
  Clock clock;
  std::int64_t lost_particles = 0;  // left the domain and were removed
  GrowthServo growth;               // used by radius_growth only
  /// Ghost exchange, migration and balance: present under MPI with more than
  /// one rank or with periodic dimensions; null in a plain serial scene.
  std::shared_ptr<Exchange> exchange;
  /// Forces summed per particle in a fixed order (by partner global id), so
  /// results do not depend on the thread or rank count. On whenever OpenMP
  /// runs more than one thread (race-free accumulation), or when asked.
  bool deterministic = false;
  /// Each wall's load this step, from this rank's particles; empty unless
  /// measured (output.wall_loads), so that no wall stage computes it otherwise.
  std::vector<WallLoad> wall_loads;
  /// The contact stress gathered by the force stages on the steps it is
  /// measured (output.stress); null on every other step.
  StressProbe* stress_probe = nullptr;
  /// The memory the case's grains will need, estimated at set-up (build_scene.hpp).
  struct Memory {
    std::int64_t particles = 0;  // particle records the case asks for (sets and insertions)
    double field_bytes = 0;      // per particle: every allocated field, wall history included (exact)
    double list_bytes = 0;       // per particle: neighbour-list rows of a dense bed (estimate)
    double total() const { return static_cast<double>(particles) * (field_bytes + list_bytes); }
  } memory;
};

}  // namespace grains::sim
