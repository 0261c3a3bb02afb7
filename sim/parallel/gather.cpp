#include "sim/parallel/gather.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <numeric>

#include "sim/parallel/bytes.hpp"
#include "sim/parallel/exchange.hpp"

namespace grains::sim {

namespace {
using bytes::put;
using bytes::take;
}  // namespace

Scene gather_scene(Scene& s) {
  const Comm& comm = s.exchange ? s.exchange->comm() : Comm::world();
  auto& p = s.particles;
  const int H = s.neighbors.history_size();
  // This rank's part: particles, bodies, histories.
  std::vector<char> mine;
  put(mine, static_cast<std::int64_t>(p.n_owned()));
  for (std::size_t i = 0; i < p.n_owned(); ++i) p.pack(i, mine);
  put(mine, static_cast<std::int64_t>(s.bodies.size()));
  for (std::size_t k = 0; k < s.bodies.size(); ++k)
    s.bodies.visit_fields([&](const char*, const char*, auto& vec) { put(mine, vec[k]); });
  std::vector<char> hist;
  std::int64_t nh = 0;
  s.neighbors.for_each_history([&](std::int64_t a, std::int64_t b, const double* h) {
    put(hist, a);
    put(hist, b);
    hist.insert(hist.end(), reinterpret_cast<const char*>(h), reinterpret_cast<const char*>(h + H));
    ++nh;
  });
  put(mine, nh);
  mine.insert(mine.end(), hist.begin(), hist.end());
  const auto lost = comm.sum(s.lost_particles);
  const auto parts = comm.gather(mine);

  Scene g;
  g.domain = s.domain;
  g.walls = s.walls;
  g.materials = s.materials;
  g.pairs = s.pairs;
  g.gravity = s.gravity;
  g.clock = s.clock;
  g.lost_particles = lost;
  g.deterministic = s.deterministic;
  g.growth = s.growth;  // the same on every rank
  g.particles.configure(p.fields(), p.wall_history_size(), p.wall_tag_size());
  g.neighbors.configure(H, s.neighbors.skin());
  g.neighbors.set_skin_fraction(s.neighbors.skin_fraction());
  g.neighbors.set_reach(s.neighbors.reach());
  g.neighbors.set_frozen(s.neighbors.frozen());
  if (!comm.root()) return g;

  ParticleStore all;
  all.configure(p.fields(), p.wall_history_size(), p.wall_tag_size());
  const std::size_t rec = p.record_bytes();
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<double>> pairs;
  for (const auto& part : parts) {
    const char* q = part.data();
    const auto n = take<std::int64_t>(q);
    for (std::int64_t k = 0; k < n; ++k, q += rec) all.unpack_owned(q);
    const auto nb = take<std::int64_t>(q);
    for (std::int64_t k = 0; k < nb; ++k)
      g.bodies.visit_fields([&](const char*, const char*, auto& vec) {
        using T = typename std::decay_t<decltype(vec)>::value_type;
        vec.push_back(take<T>(q));
      });
    const auto m = take<std::int64_t>(q);
    for (std::int64_t k = 0; k < m; ++k) {
      const auto a = take<std::int64_t>(q);
      const auto b = take<std::int64_t>(q);
      const auto* h = reinterpret_cast<const double*>(q);
      pairs.emplace(std::make_pair(a, b), std::vector<double>(h, h + H));  // first copy wins
      q += sizeof(double) * static_cast<std::size_t>(H);
    }
  }
  // Particles and bodies in global-id order.
  std::vector<std::size_t> order(all.n_owned());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&all](std::size_t a, std::size_t b) { return all.id[a] < all.id[b]; });
  all.permute(order);
  g.particles = std::move(all);
  {
    std::vector<std::size_t> bo(g.bodies.size());
    std::iota(bo.begin(), bo.end(), std::size_t{0});
    std::sort(bo.begin(), bo.end(), [&g](std::size_t a, std::size_t b) { return g.bodies.id[a] < g.bodies.id[b]; });
    g.bodies.visit_fields([&](const char*, const char*, auto& vec) {
      auto copy = vec;
      for (std::size_t k = 0; k < bo.size(); ++k) vec[k] = copy[bo[k]];
    });
    g.bodies.rebuild_index();
  }
  // The pairs with history as a list over the gathered particles (rows by the smaller id).
  auto& nl = g.neighbors;
  const auto& gp = g.particles;
  auto index_of = [&gp](std::int64_t id) {
    const auto it = std::lower_bound(gp.id.begin(), gp.id.end(), id);
    return it != gp.id.end() && *it == id ? static_cast<std::int64_t>(it - gp.id.begin()) : std::int64_t{-1};
  };
  const std::size_t n = gp.n_owned();
  nl.row_start.assign(n + 1, 0);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> entries;
  std::vector<const std::vector<double>*> hs;
  for (const auto& [key, h] : pairs) {
    const auto a = index_of(key.first), b = index_of(key.second);
    if (a < 0 || b < 0) continue;  // a particle left the domain since
    entries.emplace_back(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
    hs.push_back(&h);
  }
  // `pairs` is ordered by (id_a, id_b) and indices follow ids: entries are row-sorted.
  for (const auto& e : entries) ++nl.row_start[e.first + 1];
  std::partial_sum(nl.row_start.begin(), nl.row_start.end(), nl.row_start.begin());
  for (std::size_t k = 0; k < entries.size(); ++k) {
    nl.partner.push_back(entries[k].second);
    nl.history.insert(nl.history.end(), hs[k]->begin(), hs[k]->end());
  }
  nl.wall_near.assign(g.walls.count(), {});
  nl.wall_items.assign(g.walls.count(), {});
  NeighborList::BuildState b;
  b.time = s.clock.time;
  b.row_id = gp.id;  // no build positions: the next step rebuilds
  b.builds = s.neighbors.stats().builds;
  nl.restore(gp, std::move(b));
  return g;
}

}  // namespace grains::sim
