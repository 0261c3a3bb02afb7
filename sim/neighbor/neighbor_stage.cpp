#include "sim/neighbor/neighbor_stage.hpp"

namespace grains::sim {

void NeighborStage::run(Scene& s) {
  auto& p = s.particles;
  if (!s.neighbors.needs_rebuild(p, s.walls, s.clock.time)) return;
  // Particles that left the domain are removed (counted in the summary).
  std::vector<char> out(p.n_owned(), 0);
  bool any = false;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if (!s.domain.contains(p.x[i])) {
      out[i] = 1;
      any = true;
      ++s.lost_particles;
    }
  if (any && p.fields().has(Field::Body)) {
    // A clump leaves as a whole: all its balls go with the one that left.
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
  s.neighbors.build(p, s.walls, s.domain.lo, s.domain.hi, s.clock.time, sort_);
}

}  // namespace grains::sim
