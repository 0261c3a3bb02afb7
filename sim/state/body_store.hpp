#pragma once
// BodyStore: the rigid clumps of a scene, as a structure of arrays.
//
// A clump is a rigid body made of member balls. The balls are ordinary
// particles of the ParticleStore (so contacts, walls, neighbour lists, VTK
// and checkpoints treat them as spheres); each carries the id of its body and
// its offset from the body's centre of mass in the body frame (the `body`
// and `body_offset` particle fields). The body holds what the balls do not:
// centre of mass, velocity, orientation, angular momentum, mass and
// principal inertia, and the force and torque summed from its balls.
//
// No particle index is stored here: the neighbour build re-sorts particles,
// and each ball finds its body through its `body` field and index_of(). Body
// ids are 0..n-1 when the scene is built and never reused; index_of() maps
// an id to its current index (bodies are removed when one of their balls
// leaves the domain).
#include <algorithm>
#include <cstdint>
#include <vector>

#include "sim/state/particle_store.hpp"

namespace grains::sim {

class BodyStore {
 public:
  std::size_t size() const { return id.size(); }

  /// Appends a body at rest in rotation (L = 0); returns its index.
  std::size_t add(std::int64_t body_id, const Vec3& com, const Vec3& vel, const Quat& q, double m, const Vec3& principal,
                  double vol, int n_members) {
    id.push_back(body_id);
    x.push_back(com);
    v.push_back(vel);
    orientation.push_back(q);
    angular_momentum.push_back(Vec3::Zero());
    omega.push_back(Vec3::Zero());
    mass.push_back(m);
    inertia.push_back(principal);
    volume.push_back(vol);
    members.push_back(n_members);
    force.push_back(Vec3::Zero());
    torque.push_back(Vec3::Zero());
    rebuild_index();
    return id.size() - 1;
  }

  /// Index of the body with id `body_id`, or -1 when it was removed.
  std::int64_t index_of(std::int64_t body_id) const {
    return body_id >= 0 && static_cast<std::size_t>(body_id) < index_.size() ? index_[body_id] : -1;
  }

  /// Removes the bodies whose flag is set (order of the rest is kept).
  void remove_if(const std::vector<char>& remove) {
    visit_fields([&](const char*, const char*, auto& vec) {
      std::size_t w = 0;
      for (std::size_t b = 0; b < vec.size(); ++b)
        if (!remove[b]) vec[w++] = vec[b];
      vec.resize(w);
    });
    rebuild_index();
  }

  /// Maps ids to indices again (after add, remove or a restore).
  void rebuild_index() {
    std::int64_t max_id = -1;
    for (auto b : id) max_id = std::max(max_id, b);
    index_.assign(static_cast<std::size_t>(max_id + 1), -1);
    for (std::size_t k = 0; k < id.size(); ++k) index_[static_cast<std::size_t>(id[k])] = static_cast<std::int64_t>(k);
  }

  std::vector<std::int64_t> id;
  std::vector<Vec3> x, v;            // centre of mass (m), velocity (m/s)
  std::vector<Quat> orientation;     // body -> world
  std::vector<Vec3> angular_momentum, omega;  // world frame; omega derived from L
  std::vector<double> mass, volume;  // kg, m^3 (of the union of balls)
  std::vector<Vec3> inertia;         // principal moments, body frame, kg m^2
  std::vector<std::int32_t> members; // number of member balls
  std::vector<Vec3> force, torque;   // summed from the balls (+ gravity) in the force phase

  /// Applies fn(name, unit, vector&) to every per-body array: the one list
  /// that removal and checkpoints go through.
  template <class Fn>
  void visit_fields(Fn&& fn) {
    fn("id", "", id); fn("position", "m", x); fn("velocity", "m/s", v); fn("orientation", "", orientation);
    fn("angular_momentum", "kg m^2/s", angular_momentum); fn("angular_velocity", "rad/s", omega);
    fn("mass", "kg", mass); fn("volume", "m^3", volume); fn("inertia", "kg m^2", inertia);
    fn("members", "", members); fn("force", "N", force); fn("torque", "N m", torque);
  }

 private:
  std::vector<std::int64_t> index_;
};

}  // namespace grains::sim
