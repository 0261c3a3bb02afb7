#pragma once
// The contacts of a pair stage's list entries, into the stress probe
// (sim/state/stress_probe.hpp), after a deferred force evaluation: entry k's
// force on its row particle, zero for entries not in contact. Serial: only on
// the steps the stress is measured.
#include "sim/laws/entry_forces.hpp"
#include "sim/neighbor/neighbor_list.hpp"
#include "sim/state/stress_probe.hpp"

namespace grains::sim {

template <bool Rotation>
void probe_entries(StressProbe& probe, const ParticleStore& p, const NeighborList& nl, const EntryForces& e) {
  const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
  for (std::size_t i = 0; i < rows; ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const Vec3 f = e.force<Rotation>(k);
      if (f.squaredNorm() > 0) probe.add_pair(0, p, i, nl.partner[k], f);
    }
}

}  // namespace grains::sim
