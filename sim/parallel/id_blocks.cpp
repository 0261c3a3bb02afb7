#include "sim/parallel/id_blocks.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <tuple>
#include <numeric>

#include "sim/parallel/bytes.hpp"
#include "sim/parallel/exchange.hpp"

namespace grains::sim {

namespace {
using bytes::put;
using bytes::take;

std::size_t owner(const std::vector<std::int64_t>& cuts, std::int64_t id) {
  const auto it = std::upper_bound(cuts.begin(), cuts.end(), id);
  const auto r = static_cast<std::ptrdiff_t>(it - cuts.begin()) - 1;
  return static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(r, 0, static_cast<std::ptrdiff_t>(cuts.size()) - 2));
}

// Offset of this rank's rows and the total, from every rank's count.
std::pair<std::size_t, std::size_t> offset_and_total(const Comm& comm, std::size_t local) {
  const auto all = comm.all_gather(static_cast<std::int64_t>(local));
  std::int64_t before = 0, total = 0;
  for (int r = 0; r < comm.size(); ++r) {
    if (r < comm.rank()) before += all[static_cast<std::size_t>(r)];
    total += all[static_cast<std::size_t>(r)];
  }
  return {static_cast<std::size_t>(before), static_cast<std::size_t>(total)};
}
}  // namespace

std::vector<std::int64_t> id_block_cuts(const Comm& comm, const std::vector<std::int64_t>& ids) {
  const auto P = static_cast<std::size_t>(comm.size());
  std::int64_t lo = std::numeric_limits<std::int64_t>::max(), hi = std::numeric_limits<std::int64_t>::min();
  for (auto id : ids) lo = std::min(lo, id), hi = std::max(hi, id);
  lo = -comm.max(-lo);
  hi = comm.max(hi);
  std::vector<std::int64_t> cuts(P + 1, 0);
  if (hi < lo) return cuts;  // no ids anywhere: every block empty
  // A histogram of the ids, reduced over ranks; cuts at bin edges where the
  // running count first reaches r n / P.
  const std::int64_t span = hi - lo + 1;
  const std::int64_t bins = std::min<std::int64_t>(span, std::max<std::int64_t>(4096, 8 * static_cast<std::int64_t>(P)));
  const std::int64_t width = (span + bins - 1) / bins;
  std::vector<std::int64_t> count(static_cast<std::size_t>(bins), 0);
  for (auto id : ids) ++count[static_cast<std::size_t>((id - lo) / width)];
  comm.sum_in_place(count);
  const std::int64_t n = std::accumulate(count.begin(), count.end(), std::int64_t{0});
  cuts[0] = lo;
  cuts[P] = hi + 1;
  std::int64_t running = 0;
  std::size_t bin = 0;
  for (std::size_t r = 1; r < P; ++r) {
    const std::int64_t target = n * static_cast<std::int64_t>(r) / static_cast<std::int64_t>(P);
    while (bin < count.size() && running < target) running += count[bin++];
    cuts[r] = std::min(hi + 1, lo + static_cast<std::int64_t>(bin) * width);
  }
  return cuts;
}

IdBlock id_blocks(Scene& s) {
  const Comm& comm = s.exchange ? s.exchange->comm() : Comm::world();
  const auto P = static_cast<std::size_t>(comm.size());
  auto& p = s.particles;
  const int H = s.neighbors.history_size();
  const auto Hs = static_cast<std::size_t>(H);
  IdBlock out;
  out.lost_particles = comm.sum(s.lost_particles);

  // Particles: records to the rank of their id block, then sorted by id.
  const std::vector<std::int64_t> mine(p.id.begin(), p.id.begin() + static_cast<std::ptrdiff_t>(p.n_owned()));
  const auto cuts = id_block_cuts(comm, mine);
  std::vector<std::vector<char>> send(P);
  for (std::size_t i = 0; i < p.n_owned(); ++i) p.pack(i, send[owner(cuts, p.id[i])]);
  auto recv = comm.alltoallv(send);
  auto& q = out.particles;
  q.configure(p.fields(), p.wall_history_size(), p.wall_tag_size());
  const std::size_t rec = p.record_bytes();
  for (const auto& part : recv)
    for (std::size_t k = 0; k + rec <= part.size(); k += rec) q.unpack_owned(part.data() + k);
  {
    std::vector<std::size_t> order(q.n_owned());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&q](std::size_t a, std::size_t b) { return q.id[a] < q.id[b]; });
    q.permute(order);
  }
  std::tie(out.particle_offset, out.particle_total) = offset_and_total(comm, q.n_owned());

  // Bodies (clumps): the same with body ids.
  {
    const auto bcuts = id_block_cuts(comm, s.bodies.id);
    for (auto& b : send) b.clear();
    for (std::size_t k = 0; k < s.bodies.size(); ++k) {
      auto& b = send[owner(bcuts, s.bodies.id[k])];
      s.bodies.visit_fields([&](const char*, const char*, auto& vec) { put(b, vec[k]); });
    }
    recv = comm.alltoallv(send);
    BodyStore got;
    for (const auto& part : recv) {
      const char* r = part.data();
      while (r < part.data() + part.size())
        got.visit_fields([&](const char*, const char*, auto& vec) {
          using T = typename std::decay_t<decltype(vec)>::value_type;
          vec.push_back(take<T>(r));
        });
    }
    std::vector<std::size_t> bo(got.size());
    std::iota(bo.begin(), bo.end(), std::size_t{0});
    std::sort(bo.begin(), bo.end(), [&got](std::size_t a, std::size_t b) { return got.id[a] < got.id[b]; });
    got.visit_fields([&](const char*, const char*, auto& vec) {
      auto copy = vec;
      for (std::size_t k = 0; k < bo.size(); ++k) vec[k] = copy[bo[k]];
    });
    got.rebuild_index();
    out.bodies = std::move(got);
    std::tie(out.body_offset, out.body_total) = offset_and_total(comm, out.bodies.size());
  }

  // Histories: to the rank of the row's (smaller) id; a pair between an owned
  // particle and a ghost comes from both ranks, identical: the first copy in
  // rank order is kept, as gather_scene does.
  for (auto& b : send) b.clear();
  s.neighbors.for_each_history([&](std::int64_t a, std::int64_t b, const double* h) {
    auto& buf = send[owner(cuts, a)];
    put(buf, a);
    put(buf, b);
    buf.insert(buf.end(), reinterpret_cast<const char*>(h), reinterpret_cast<const char*>(h + Hs));
  });
  recv = comm.alltoallv(send);
  std::map<std::pair<std::int64_t, std::int64_t>, const double*> pairs;
  for (const auto& part : recv) {
    const char* r = part.data();
    while (r < part.data() + part.size()) {
      const auto a = take<std::int64_t>(r);
      const auto b = take<std::int64_t>(r);
      pairs.emplace(std::make_pair(a, b), reinterpret_cast<const double*>(r));  // recv outlives the map's use
      r += sizeof(double) * Hs;
    }
  }
  auto local_index = [&q](std::int64_t id) {
    const auto it = std::lower_bound(q.id.begin(), q.id.end(), id);
    return it != q.id.end() && *it == id ? static_cast<std::int64_t>(it - q.id.begin()) : std::int64_t{-1};
  };
  // Partners' positions in the global order, asked of the ranks holding them.
  std::vector<std::vector<std::int64_t>> asked(P);
  for (const auto& kv : pairs)
    if (local_index(kv.first.first) >= 0) asked[owner(cuts, kv.first.second)].push_back(kv.first.second);
  for (std::size_t r = 0; r < P; ++r) {
    send[r].assign(reinterpret_cast<const char*>(asked[r].data()),
                   reinterpret_cast<const char*>(asked[r].data() + asked[r].size()));
  }
  auto questions = comm.alltoallv(send);
  for (std::size_t r = 0; r < P; ++r) {
    send[r].clear();
    const char* c = questions[r].data();
    while (c < questions[r].data() + questions[r].size()) {
      const auto i = local_index(take<std::int64_t>(c));
      put(send[r], i < 0 ? std::int64_t{-1} : static_cast<std::int64_t>(out.particle_offset) + i);
    }
  }
  const auto answers = comm.alltoallv(send);
  std::vector<const char*> next(P);
  for (std::size_t r = 0; r < P; ++r) next[r] = answers[r].data();
  // `pairs` is ordered by (id_a, id_b), and rows follow ids: entries come out row-sorted.
  const std::size_t n = q.n_owned();
  std::vector<std::uint32_t> count(n + 1, 0);
  for (const auto& [key, h] : pairs) {
    const auto a = local_index(key.first);
    if (a < 0) continue;  // the row's particle left the domain since
    const auto b = take<std::int64_t>(next[owner(cuts, key.second)]);
    if (b < 0) continue;  // so did the partner
    ++count[static_cast<std::size_t>(a) + 1];
    out.partner.push_back(static_cast<std::uint32_t>(b));
    out.history.insert(out.history.end(), h, h + Hs);
  }
  std::tie(out.entry_offset, out.entry_total) = offset_and_total(comm, out.partner.size());
  std::partial_sum(count.begin(), count.end(), count.begin());
  out.row_start.resize(n + 1);
  for (std::size_t i = 0; i <= n; ++i) out.row_start[i] = static_cast<std::uint32_t>(out.entry_offset + count[i]);
  return out;
}

}  // namespace grains::sim
