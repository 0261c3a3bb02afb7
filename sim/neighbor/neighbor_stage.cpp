#include "sim/neighbor/neighbor_stage.hpp"

#include <algorithm>
#include <vector>

#include "sim/neighbor/whole_clumps.hpp"
#include "sim/parallel/exchange.hpp"

namespace grains::sim {

namespace {

// Particles that left the domain (through a non-periodic face) are removed
// and counted in the summary; a clump leaves as a whole. `per_particle`
// (owned values) is compacted alongside.
void remove_lost(Scene& s, std::vector<double>& per_particle) {
  auto& p = s.particles;
  std::vector<char> out(p.n_owned(), 0);
  bool any = false;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if (!s.domain.contains(p.x[i])) {
      out[i] = 1;
      any = true;
      ++s.lost_particles;
    }
  if (!any) return;
  s.lost_particles += flag_whole_clumps(s, out);
  p.remove_if(out);
  std::size_t m = 0;
  for (std::size_t i = 0; i < per_particle.size() && i < out.size(); ++i)
    if (!out[i]) per_particle[m++] = per_particle[i];
  per_particle.resize(std::min(m, per_particle.size()));
}

}  // namespace

std::size_t flag_whole_clumps(Scene& s, std::vector<char>& out) {
  auto& p = s.particles;
  if (!p.fields().has(Field::Body)) return 0;
  std::vector<char> gone(s.bodies.size(), 0);
  for (std::size_t i = 0; i < out.size(); ++i)
    if (out[i] && p.body[i] >= 0) gone[static_cast<std::size_t>(s.bodies.index_of(p.body[i]))] = 1;
  std::size_t added = 0;
  for (std::size_t i = 0; i < out.size(); ++i)
    if (!out[i] && p.body[i] >= 0 && gone[static_cast<std::size_t>(s.bodies.index_of(p.body[i]))]) {
      out[i] = 1;
      ++added;
    }
  s.bodies.remove_if(gone);
  return added;
}

void NeighborStage::run(Scene& s) {
  auto& p = s.particles;
  bool rebuild = s.neighbors.needs_rebuild(p, s.walls, s.clock.time);
  if (s.exchange) rebuild = s.exchange->comm().any(rebuild);  // all ranks together
  const double now = s.clock.time + s.clock.dt;  // the drift's state (the clock moves on after the kick)
  if (!rebuild) {
    if (s.exchange) s.exchange->update_ghosts(p, now);
    return;
  }
  full_update(s, sort_, now);
}

void NeighborStage::full_update(Scene& s, bool sort, double time, bool canonical) {
  auto& p = s.particles;
  // The work estimate for the load balance needs the old list with its ghosts.
  std::vector<double> work;
  if (s.exchange && s.exchange->comm().parallel()) work = Exchange::work_weights(p, s.neighbors);
  p.clear_ghosts();
  remove_lost(s, work);
  if (!s.exchange) {
    s.neighbors.build(p, s.walls, s.domain.lo, s.domain.hi, s.clock.time, sort);
    return;
  }
  s.exchange->migrate(s, &work, time);
  if (canonical) {
    std::vector<std::size_t> order(p.n_owned());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
    p.permute(order);
  }
  if (sort) s.neighbors.sort_by_cell(p, s.domain.lo, s.domain.hi);
  s.exchange->build_ghosts(p, time);
  s.neighbors.build(p, s.walls, s.domain.lo, s.domain.hi, s.clock.time, false);
  s.exchange->drop_unlisted_images(p, s.neighbors);
}

}  // namespace grains::sim
