#pragma once
// The state of a decomposed run redistributed into contiguous blocks of the
// global-id order, one block per rank: what a parallel (MPI-IO) checkpoint
// writes, each rank its own rows at its offset, so that the file is the same
// as the one written from gather_scene (gather.hpp) on rank 0 — particles
// and bodies sorted by global id, the pairs with contact history as CSR rows
// by the smaller id with partners as indices into that order — without any
// rank holding more than its share.
//
// How: the id range is cut at quantiles of a histogram of ids reduced over
// ranks (so blocks hold about n/P particles even when ids have gaps), the
// particle records and bodies go to the rank of their block in one
// all-to-all, histories to the rank of their row's id; a second all-to-all
// asks the owners of the partners for their positions in the global order.
// Pairs whose particles left the domain are dropped, as in gather_scene.
#include <cstdint>
#include <vector>

#include "sim/parallel/comm.hpp"
#include "sim/scene/scene.hpp"

namespace grains::sim {

struct IdBlock {
  ParticleStore particles;  // this rank's block, sorted by global id (owned only)
  BodyStore bodies;         // this rank's block of bodies, sorted by body id
  std::size_t particle_offset = 0, particle_total = 0;  // rows in the global order
  std::size_t body_offset = 0, body_total = 0;
  /// Contact history as CSR rows of this block: row_start has
  /// particles.n_owned() + 1 entries, already shifted by entry_offset (so
  /// they are the global values); partner holds global particle indices.
  std::vector<std::uint32_t> row_start, partner;
  std::vector<double> history;  // history_size doubles per entry
  std::size_t entry_offset = 0, entry_total = 0;
  std::int64_t lost_particles = 0;  // summed over ranks
};

/// Collective: every rank must call it; each gets its block.
IdBlock id_blocks(Scene& s);

/// Cuts of the id range into comm.size() blocks holding about the same
/// number of ids: block r holds ids in [cuts[r], cuts[r+1]). Collective.
std::vector<std::int64_t> id_block_cuts(const Comm& comm, const std::vector<std::int64_t>& ids);

}  // namespace grains::sim
