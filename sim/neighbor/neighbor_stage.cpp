#include "sim/neighbor/neighbor_stage.hpp"

#include "sim/parallel/exchange.hpp"

namespace grains::sim {

namespace {

// Particles that left the domain (through a non-periodic face) are removed
// and counted in the summary; a clump leaves as a whole.
void remove_lost(Scene& s) {
  auto& p = s.particles;
  std::vector<char> out(p.n_owned(), 0);
  bool any = false;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if (!s.domain.contains(p.x[i])) {
      out[i] = 1;
      any = true;
      ++s.lost_particles;
    }
  if (any && p.fields().has(Field::Body)) {
    std::vector<char> gone(s.bodies.size(), 0);
    for (std::size_t i = 0; i < p.n_owned(); ++i)
      if (out[i] && p.body[i] >= 0) gone[static_cast<std::size_t>(s.bodies.index_of(p.body[i]))] = 1;
    for (std::size_t i = 0; i < p.n_owned(); ++i)
      if (!out[i] && p.body[i] >= 0 && gone[static_cast<std::size_t>(s.bodies.index_of(p.body[i]))]) {
        out[i] = 1;
        ++s.lost_particles;
      }
    s.bodies.remove_if(gone);
  }
  if (any) p.remove_if(out);
}

}  // namespace

void NeighborStage::run(Scene& s) {
  auto& p = s.particles;
  bool rebuild = s.neighbors.needs_rebuild(p, s.walls, s.clock.time);
  if (s.exchange) rebuild = s.exchange->comm().any(rebuild);  // all ranks together
  if (!rebuild) {
    if (s.exchange) s.exchange->update_ghosts(p);
    return;
  }
  full_update(s, sort_);
}

void NeighborStage::full_update(Scene& s, bool sort) {
  auto& p = s.particles;
  p.clear_ghosts();
  remove_lost(s);
  if (!s.exchange) {
    s.neighbors.build(p, s.walls, s.domain.lo, s.domain.hi, s.clock.time, sort);
    return;
  }
  s.exchange->migrate(s);
  if (sort) s.neighbors.sort_by_cell(p, s.domain.lo, s.domain.hi);
  s.exchange->build_ghosts(p);
  s.neighbors.build(p, s.walls, s.domain.lo, s.domain.hi, s.clock.time, false);
}

}  // namespace grains::sim
