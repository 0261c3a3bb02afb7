#pragma once
// The deterministic, thread-parallel way of summing pair forces
// (Scene::deterministic): each list entry's force and torques are computed
// into per-entry slots (rows in parallel, no two threads write the same
// slot), then every owned particle sums its entries in the order of the
// other particle's global id (NeighborList::gather_*). The sum therefore
// does not depend on the thread count, the rank count or the local order
// of particles, and there are no write races.
#include <vector>

#include "sim/neighbor/neighbor_list.hpp"
#include "sim/state/particle_store.hpp"

namespace grains::sim {

struct EntryForces {
  std::vector<Vec3> f;       // force on the row particle (the partner gets -f)
  std::vector<Vec3> ti, tj;  // torque on the row particle, on the partner
  template <bool Rotation>
  void resize(std::size_t entries) {
    f.resize(entries);
    if constexpr (Rotation) {
      ti.resize(entries);
      tj.resize(entries);
    }
  }
  template <bool Rotation>
  void zero(std::size_t k) {
    f[k].setZero();
    if constexpr (Rotation) {
      ti[k].setZero();
      tj[k].setZero();
    }
  }
};

/// Adds each owned particle's entries to its force (and torque), in the
/// list's gather order.
template <bool Rotation>
inline void gather_entry_forces(ParticleStore& p, const NeighborList& nl, const EntryForces& e) {
  const auto n = static_cast<std::ptrdiff_t>(p.n_owned());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    Vec3 f = Vec3::Zero(), t = Vec3::Zero();
    for (auto g = nl.gather_start[i]; g < nl.gather_start[i + 1]; ++g) {
      const std::uint32_t code = nl.gather_entry[g], k = code >> 1;
      if (code & 1u) {
        f -= e.f[k];
        if constexpr (Rotation) t += e.tj[k];
      } else {
        f += e.f[k];
        if constexpr (Rotation) t += e.ti[k];
      }
    }
    p.f[i] += f;
    if constexpr (Rotation) p.torque[i] += t;
  }
}

}  // namespace grains::sim
