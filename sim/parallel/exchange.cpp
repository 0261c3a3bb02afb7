#include "sim/parallel/exchange.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <unordered_map>

#include "sim/parallel/bytes.hpp"

namespace grains::sim {

namespace {

using bytes::put;
using bytes::take;

void pack_body(BodyStore& b, std::size_t k, std::vector<char>& buf) {
  b.visit_fields([&](const char*, const char*, auto& vec) { put(buf, vec[k]); });
}

void unpack_body(BodyStore& b, const char*& r) {
  b.visit_fields([&](const char*, const char*, auto& vec) {
    using T = typename std::decay_t<decltype(vec)>::value_type;
    vec.push_back(take<T>(r));
  });
}

// A ghost update within one rank (the images of a serial run's periodic
// faces): the kinematic fields of particles from[k] copied to to + k, field
// by field, as pack_kinematics and unpack_kinematics would carry them with
// no shift, without the buffer. Every source lies before `to` (a swap sends
// only what existed before its own ghosts).
void copy_kinematics(ParticleStore& p, const std::vector<std::uint32_t>& from, std::size_t to) {
  p.declare_fields([&](const ParticleStore::FieldInfo& f, auto member, auto) {
    if (!f.kinematic) return;
    auto& vec = p.*member;
    if constexpr (std::is_same_v<std::decay_t<decltype(vec)>, std::vector<Vec3>>) {
      if (member == &ParticleStore::x) {  // as pack_kinematics writes the image's position: x + shift
        for (std::size_t k = 0; k < from.size(); ++k) vec[to + k] = vec[from[k]] + Vec3::Zero();
        return;
      }
    }
    const auto w = static_cast<std::size_t>(f.width);
    for (std::size_t k = 0; k < from.size(); ++k)
      for (std::size_t c = 0; c < w; ++c) vec[(to + k) * w + c] = vec[from[k] * w + c];
  });
}

}  // namespace

Exchange::Exchange(const Comm& comm, const Domain& domain, double cutoff, ExchangeOptions opt)
    : comm_(comm), domain_(domain), dec_(domain, comm.size(), cutoff, opt.dims), cut_(cutoff), opt_(opt) {
  for (int d = 0; d < 3; ++d)
    if (domain.periodic[d] && domain.hi[d] - domain.lo[d] < 2 * cutoff)
      throw std::runtime_error(std::string("the periodic box is too small along ") + "xyz"[d] + ": " +
                               std::to_string(domain.hi[d] - domain.lo[d]) +
                               " m, it must be at least twice the ghost cut-off " + std::to_string(cutoff) +
                               " m (largest diameter + skin) so that a pair meets only one image");
}

void Exchange::wrap(Scene& s, double time) {
  if (!domain_.any_periodic()) return;
  auto& p = s.particles;
  auto& b = s.bodies;
  std::vector<Vec3> body_shift(b.size(), Vec3::Zero());
  for (std::size_t k = 0; k < b.size(); ++k) body_shift[k] = domain_.wrap(b.x[k]);
  const bool clumps = p.fields().has(Field::Body);
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    if (clumps && p.body[i] >= 0)
      p.x[i] += body_shift[static_cast<std::size_t>(b.index_of(p.body[i]))];
    else if (domain_.shear.on())  // across the sheared face: displaced and slowed (or sped up)
      domain_.wrap(p.x[i], p.v[i], time);
    else
      domain_.wrap(p.x[i]);
  }
}

void Exchange::distribute_initial(Scene& s, const std::array<std::vector<double>, 3>* saved_cuts) {
  auto& p = s.particles;
  auto& b = s.bodies;
  wrap(s, s.clock.time);
  if (!comm_.parallel()) return;
  keep_cuts_once_ = saved_cuts && dec_.set_cuts(*saved_cuts);
  // Every rank holds all particles: balance on them (a one-rank view, no
  // sums over ranks) when the uniform cuts would leave the load uneven.
  const int me = comm_.rank();
  {
    std::vector<std::int64_t> load(static_cast<std::size_t>(comm_.size()), 0);
    for (std::size_t i = 0; i < p.n_owned(); ++i) ++load[static_cast<std::size_t>(dec_.owner(p.x[i]))];
    std::int64_t mx = 0;
    for (auto l : load) mx = std::max(mx, l);
    const double mean = static_cast<double>(p.n_owned()) / comm_.size();
    if (!keep_cuts_once_ && mean > 0 && mx / mean > opt_.balance_threshold) {
      Comm one;
      if (dec_.balance(p.x, p.n_owned(), one)) ++stats_.rebalances;
    }
  }
  std::vector<char> gone_body(b.size(), 0);
  for (std::size_t k = 0; k < b.size(); ++k) gone_body[k] = dec_.owner(b.x[k]) != me;
  const bool clumps = p.fields().has(Field::Body);
  std::vector<char> gone(p.n_owned(), 0);
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    gone[i] = clumps && p.body[i] >= 0 ? gone_body[static_cast<std::size_t>(b.index_of(p.body[i]))]
                                       : dec_.owner(p.x[i]) != me;
  p.remove_if(gone);
  b.remove_if(gone_body);
  stats_.imbalance = Decomposition::imbalance(p.n_owned(), comm_);
}

std::vector<double> Exchange::work_weights(const ParticleStore& p, const NeighborList& list) {
  const std::size_t n = p.n_owned();
  std::vector<double> w(n, 1.0);
  const std::size_t rows = list.row_start.empty() ? 0 : list.row_start.size() - 1;
  // A list from before the last change of the particle set (a restart, the
  // first update) does not describe these particles: count them alone.
  if (rows == 0 || rows != p.size() || list.partner.size() != list.row_start.back()) return w;
  for (std::size_t r = 0; r < rows; ++r)
    for (auto k = list.row_start[r]; k < list.row_start[r + 1]; ++k) {
      const std::size_t j = list.partner[k];
      const bool ro = r < n, jo = j < n;
      if (ro && jo) {
        w[r] += 0.5;
        w[j] += 0.5;
      } else if (ro) {
        w[r] += 1;
      } else if (jo) {
        w[j] += 1;
      }
    }
  return w;
}

void Exchange::migrate(Scene& s, const std::vector<double>* work, double time) {
  auto& p = s.particles;
  auto& b = s.bodies;
  ++stats_.full_updates;
  wrap(s, time);
  if (!comm_.parallel()) return;
  const double* w = work && work->size() == p.n_owned() ? work->data() : nullptr;
  double load = static_cast<double>(p.n_owned());
  if (w) {
    load = 0;
    for (std::size_t i = 0; i < p.n_owned(); ++i) load += w[i];
  }
  stats_.imbalance = Decomposition::imbalance(load, comm_);
  if (!keep_cuts_once_ && stats_.imbalance > opt_.balance_threshold && dec_.balance(p.x, p.n_owned(), comm_, w))
    ++stats_.rebalances;
  keep_cuts_once_ = false;

  const int me = comm_.rank();
  const auto P = static_cast<std::size_t>(comm_.size());
  std::vector<int> bdest(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) bdest[k] = dec_.owner(b.x[k]);
  const bool clumps = p.fields().has(Field::Body);
  const std::size_t n = p.n_owned();
  std::vector<int> dest(n);
  std::unordered_map<std::int64_t, int> leaving;  // global id -> destination
  for (std::size_t i = 0; i < n; ++i) {
    dest[i] = clumps && p.body[i] >= 0 ? bdest[static_cast<std::size_t>(b.index_of(p.body[i]))] : dec_.owner(p.x[i]);
    if (dest[i] != me) leaving.emplace(p.id[i], dest[i]);
  }
  // Three sections per destination: particles, bodies, pair histories.
  std::vector<std::vector<char>> pbuf(P), bbuf(P), hbuf(P);
  std::vector<std::int64_t> np(P, 0), nb(P, 0), nh(P, 0);
  std::vector<char> gone(n, 0), gone_body(b.size(), 0);
  for (std::size_t i = 0; i < n; ++i)
    if (dest[i] != me) {
      p.pack(i, pbuf[static_cast<std::size_t>(dest[i])]);
      ++np[static_cast<std::size_t>(dest[i])];
      gone[i] = 1;
    }
  for (std::size_t k = 0; k < b.size(); ++k)
    if (bdest[k] != me) {
      pack_body(b, k, bbuf[static_cast<std::size_t>(bdest[k])]);
      ++nb[static_cast<std::size_t>(bdest[k])];
      gone_body[k] = 1;
    }
  const int H = s.neighbors.history_size();
  if (H > 0 && !leaving.empty()) {
    s.neighbors.for_each_history([&](std::int64_t a, std::int64_t c, const double* h) {
      const auto ia = leaving.find(a), ic = leaving.find(c);
      int to[2] = {ia == leaving.end() ? -1 : ia->second, ic == leaving.end() ? -1 : ic->second};
      if (to[1] == to[0]) to[1] = -1;
      for (int t : to) {
        if (t < 0) continue;
        auto& buf = hbuf[static_cast<std::size_t>(t)];
        put(buf, a);
        put(buf, c);
        buf.insert(buf.end(), reinterpret_cast<const char*>(h), reinterpret_cast<const char*>(h + H));
        ++nh[static_cast<std::size_t>(t)];
      }
    });
  }
  std::vector<std::vector<char>> send(P);
  std::int64_t sent = 0;
  for (std::size_t r = 0; r < P; ++r) {
    if (static_cast<int>(r) == me) continue;
    auto& o = send[r];
    put(o, np[r]);
    o.insert(o.end(), pbuf[r].begin(), pbuf[r].end());
    put(o, nb[r]);
    o.insert(o.end(), bbuf[r].begin(), bbuf[r].end());
    put(o, nh[r]);
    o.insert(o.end(), hbuf[r].begin(), hbuf[r].end());
    sent += np[r];
  }
  stats_.migrated += sent;
  p.remove_if(gone);
  b.remove_if(gone_body);
  const auto recv = comm_.alltoallv(send);
  const std::size_t rec = p.record_bytes();
  for (std::size_t r = 0; r < P; ++r) {
    if (static_cast<int>(r) == me || recv[r].empty()) continue;
    const char* q = recv[r].data();
    const auto cnt = take<std::int64_t>(q);
    for (std::int64_t k = 0; k < cnt; ++k, q += rec) p.unpack_owned(q);
    const auto cb = take<std::int64_t>(q);
    for (std::int64_t k = 0; k < cb; ++k) unpack_body(b, q);
    const auto ch = take<std::int64_t>(q);
    for (std::int64_t k = 0; k < ch; ++k) {
      const auto a = take<std::int64_t>(q);
      const auto c = take<std::int64_t>(q);
      s.neighbors.import_history(a, c, reinterpret_cast<const double*>(q));
      q += sizeof(double) * static_cast<std::size_t>(H);
    }
  }
  b.rebuild_index();
}

double Exchange::sheared(const Swap& sw, double xf, signed char wrap, double time) const {
  const int f = domain_.shear.flow;
  const double Lf = domain_.hi[f] - domain_.lo[f];
  // The offset as U t less the whole periods taken off at the build: the
  // same bits whenever the list was built within the same period.
  const double offset = domain_.shear_travel(time) - sw.offset_periods * Lf;
  return xf + sw.shear_side * offset + wrap * Lf;
}

void Exchange::build_ghosts(ParticleStore& p, double time) {
  swaps_.clear();
  const int me = comm_.rank();
  const Vec3 lo = dec_.lo(me), hi = dec_.hi(me);
  const std::size_t rec = p.record_bytes();
  // A grain j is a partner of an owned grain i when |x_i - x_j| < r_i + r_j +
  // skin (+ reach), and x_i lies in the slab (or within a clump's extent of
  // it): j within cut_ - R + r_j of the face, R the largest radius, suffices.
  const double R = opt_.largest_radius;
  int tag = 100;
  auto cut_of = [&](std::size_t i) { return R > 0 ? cut_ - R + std::min(p.radius[i], R) : cut_; };
  // Room for the ghosts before they arrive, at the first build and whenever
  // the fields did not keep enough from the last: from the owned grains
  // near each face with a neighbour (one near two faces also has an image
  // at their edge).
  if (!ghosts_sized_ || p.room() < p.size() + stats_.images_built + stats_.images_built / 16) {
    ghosts_sized_ = true;
    std::array<bool, 6> to{};
    for (int d = 0; d < 3; ++d)
      for (int s = 0; s < 2; ++s) {
        bool w = false;
        to[2 * d + s] = (dec_.dims()[d] > 1 || domain_.periodic[d]) && dec_.neighbor(me, d, s ? 1 : -1, w) >= 0;
      }
    std::size_t images = 0;
    for (std::size_t i = 0; i < p.n_owned(); ++i) {
      const double c = cut_of(i);
      std::size_t k = 1;
      for (int d = 0; d < 3; ++d)
        k *= 1 + static_cast<std::size_t>(to[2 * d] && p.x[i][d] < lo[d] + c) +
             static_cast<std::size_t>(to[2 * d + 1] && p.x[i][d] >= hi[d] - c);
      images += k - 1;
    }
    p.reserve_more(images + images / 16);
  }
  // With Lees–Edwards boundaries the gradient's images first, so that the
  // images displaced along the flow get their own images across the flow.
  std::array<int, 3> order{0, 1, 2};
  if (domain_.shear.on()) {
    const int g = domain_.shear.gradient;
    order = {g, g == 0 ? 1 : 0, g == 2 ? 1 : 2};
  }
  // A dimension's two swaps (towards -1, then +1) choose from the grains
  // there before either (owned, and the earlier dimensions' ghosts), so
  // their messages travel together (two rounds per dimension, the sizes and
  // the records, not four); the ghosts arrive in the swaps' order.
  for (const int d : order) {
    if (dec_.dims()[d] == 1 && !domain_.periodic[d]) continue;
    const std::size_t n_sel = p.size();
    const double L = domain_.hi[d] - domain_.lo[d];
    std::array<Swap, 2> pair;
    transfers_.clear();
    for (std::size_t side = 0; side < 2; ++side) {
      const int dir = side == 0 ? -1 : +1;
      Swap& sw = pair[side];
      bool wd = false, ws = false;
      sw.dest = dec_.neighbor(me, d, dir, wd);
      sw.src = dec_.neighbor(me, d, -dir, ws);
      if (ws) sw.recv_shift[d] = -dir * L;
      if (ws && domain_.shear.on() && d == domain_.shear.gradient) {
        sw.shear_side = -dir;
        const int f = domain_.shear.flow;
        sw.offset_periods = std::floor(domain_.shear_travel(time) / (domain_.hi[f] - domain_.lo[f]));
      }
      sbufs_[side].clear();
      if (sw.dest >= 0) {
        for (std::size_t i = 0; i < n_sel; ++i) {
          const double xd = p.x[i][d];
          const double cut = cut_of(i);
          if (dir < 0 ? xd < lo[d] + cut : xd >= hi[d] - cut) sw.send.push_back(static_cast<std::uint32_t>(i));
        }
        p.pack_records(sw.send, sbufs_[side]);
      }
      transfers_.push_back({&sbufs_[side], sw.dest, &rbufs_[side], sw.src, tag + 2 * static_cast<int>(side)});
    }
    comm_.sendrecv(transfers_);
    tag += 4;
    for (std::size_t side = 0; side < 2; ++side) {
      Swap& sw = pair[side];
      const auto& rb = rbufs_[side];
      sw.recv_start = p.size();
      sw.recv_count = rb.size() / rec;
      p.unpack_ghosts(rb.data(), sw.recv_count, sw.recv_shift);
      if (sw.shear_side != 0) {
        // Displaced along the flow (into the cell's range there: the rank
        // holds the whole flow axis) and moving with the image.
        const int f = domain_.shear.flow;
        const double Lf = domain_.hi[f] - domain_.lo[f];
        sw.flow_wrap.resize(sw.recv_count);
        for (std::size_t k = 0; k < sw.recv_count; ++k) {
          const std::size_t g = sw.recv_start + k;
          const double xf = sheared(sw, p.x[g][f], 0, time);
          sw.flow_wrap[k] = static_cast<signed char>(-std::floor((xf - domain_.lo[f]) / Lf));
          p.x[g][f] = sheared(sw, p.x[g][f], sw.flow_wrap[k], time);
          p.v[g][f] += sw.shear_side * domain_.shear_speed();
        }
      }
      swaps_.push_back(std::move(sw));
    }
  }
  stats_.ghosts = stats_.images_built = p.n_ghost();
}

void Exchange::drop_unlisted_images(ParticleStore& p, NeighborList& list) {
  // A ghost is needed when a list entry has it, when a needed ghost of a
  // later swap is its image, or when a swap to another rank sends it. Only
  // this rank's own images can go: another rank sends what it chose.
  // (Per ghost only: the owned grains all stay.)
  const std::size_t n = p.n_owned(), ghosts = p.n_ghost();
  if (ghosts == 0) return;
  // Without an image of this rank's own (no periodic axis held whole), none can go.
  if (std::none_of(swaps_.begin(), swaps_.end(), [&](const Swap& sw) { return local(sw); })) return;
  std::vector<char> need(ghosts, 0);
  auto mark = [&](std::size_t i) {
    if (i >= n) need[i - n] = 1;
  };
  for (std::size_t r = 0; r + 1 < list.row_start.size(); ++r)
    if (list.row_start[r] < list.row_start[r + 1]) {
      mark(r);
      for (auto k = list.row_start[r]; k < list.row_start[r + 1]; ++k) mark(list.partner[k]);
    }
  bool any = false;
  for (std::size_t k = swaps_.size(); k-- > 0;) {
    const auto& sw = swaps_[k];
    if (!local(sw)) {
      for (const auto i : sw.send) mark(i);
      for (std::size_t m = 0; m < sw.recv_count; ++m) need[sw.recv_start + m - n] = 1;  // another rank's choice
      continue;
    }
    for (std::size_t m = 0; m < sw.recv_count; ++m) {
      if (need[sw.recv_start + m - n])
        mark(sw.send[m]);
      else
        any = true;
    }
  }
  if (!any) return;
  std::vector<std::uint32_t> to(ghosts, NeighborList::kGone);
  std::size_t count = n;
  for (std::size_t g = 0; g < ghosts; ++g)
    if (need[g]) to[g] = static_cast<std::uint32_t>(count++);
  const auto moved = [&](std::uint32_t i) { return i < n ? i : to[i - n]; };
  // Each swap's ghosts follow those of the swaps before it.
  std::size_t next = n;
  for (auto& sw : swaps_) {
    const bool own = local(sw);
    std::size_t kept = 0;
    for (std::size_t m = 0; m < sw.send.size(); ++m) {
      if (own && !need[sw.recv_start + m - n]) continue;
      sw.send[kept] = moved(sw.send[m]);
      if (own && !sw.flow_wrap.empty()) sw.flow_wrap[kept] = sw.flow_wrap[m];
      ++kept;
    }
    sw.send.resize(kept);
    std::size_t received = 0;
    for (std::size_t m = 0; m < sw.recv_count; ++m) received += need[sw.recv_start + m - n];
    if (own && !sw.flow_wrap.empty()) sw.flow_wrap.resize(received);
    sw.recv_start = next;
    sw.recv_count = received;
    next += received;
  }
  p.keep_ghosts(need);
  list.renumber_ghosts(n, to, count);
  stats_.ghosts = p.n_ghost();
}

void Exchange::set_domain(const Domain& d) {
  const int g = d.shear.gradient;
  dec_.resize(g, d.lo[g], d.hi[g]);
  const double L = d.hi[g] - d.lo[g];
  for (auto& sw : swaps_)
    if (sw.recv_shift[g] != 0) sw.recv_shift[g] = std::copysign(L, sw.recv_shift[g]);
  domain_ = d;
}

void Exchange::update_ghosts(ParticleStore& p, double time) {
  const std::size_t kb = p.kinematic_bytes();
  const int f = domain_.shear.flow;
  // build_ghosts makes two swaps per dimension (towards -1, then +1), both
  // chosen from the grains there before either (owned and the earlier
  // dimensions' ghosts): the pair's messages travel together.
  for (std::size_t a = 0; a < swaps_.size(); a += 2) {
    const std::size_t b = std::min(a + 2, swaps_.size());
    transfers_.clear();
    for (std::size_t k = a; k < b; ++k) {
      const auto& sw = swaps_[k];
      if (local(sw)) {
        copy_kinematics(p, sw.send, sw.recv_start);
        continue;
      }
      auto& sb = sbufs_[k - a];
      auto& rb = rbufs_[k - a];
      p.pack_kinematics(sw.send, sb);
      rb.resize(sw.recv_count * kb);
      transfers_.push_back({&sb, sw.dest, &rb, sw.src, static_cast<int>(100 + 2 * k)});
    }
    if (!transfers_.empty()) comm_.sendrecv_known(transfers_);
    for (const auto& t : transfers_) {
      const auto& sw = swaps_[a + static_cast<std::size_t>(t.recv - rbufs_.data())];  // rbufs_[k - a] is swap k's
      p.unpack_kinematics(sw.recv_start, sw.recv_count, t.recv->data());
    }
    for (std::size_t k = a; k < b; ++k) {
      const auto& sw = swaps_[k];
      const bool shift = sw.recv_shift.squaredNorm() > 0;
      for (std::size_t n = 0; n < sw.recv_count; ++n) {
        const std::size_t g = sw.recv_start + n;
        if (shift) p.x[g] += sw.recv_shift;
        if (sw.shear_side != 0) {
          p.x[g][f] = sheared(sw, p.x[g][f], sw.flow_wrap[n], time);
          p.v[g][f] += sw.shear_side * domain_.shear_speed();
        }
      }
    }
  }
}

}  // namespace grains::sim
