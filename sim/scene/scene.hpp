#pragma once
// The state of a run: particles, walls, materials, neighbour lists, clock.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/laws/material.hpp"
#include "sim/neighbor/neighbor_list.hpp"
#include "sim/state/body_store.hpp"
#include "sim/state/particle_store.hpp"
#include "sim/walls/walls.hpp"

namespace grains::sim {

struct Domain {
  Vec3 lo{0, 0, 0};
  Vec3 hi{1, 1, 1};
  bool contains(const Vec3& x) const {
    return (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all();
  }
};

struct Clock {
  double time = 0;      // simulated time, s
  double dt = 0;        // time step, s
  double end_time = 0;  // s
  std::int64_t step = 0;
  std::int64_t n_steps = 0;  // total steps of the run
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
};

}  // namespace grains::sim
