#include "sim/insert/insertion_stage.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <numeric>
#include <sstream>

#include "sim/parallel/bytes.hpp"
#include "sim/parallel/comm.hpp"
#include "sim/parallel/exchange.hpp"
#include "sim/scene/build_scene.hpp"

namespace grains::sim {

namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

using bytes::put;
using bytes::take;

// One grain of the scene as sent to rank 0: id, kind, centre, radius or
// semi-axes and orientation.
struct Record {
  std::int64_t id;
  std::int32_t ellipsoid;
  double x[3], r, axes[3], q[4];
};

const char* method_name(InsertionConfig::Method m) { return m == InsertionConfig::Method::Fft ? "fft" : "random"; }

}  // namespace

insert::SceneGrains gather_scene_grains(const Scene& s) {
  const auto& p = s.particles;
  const bool ell = p.fields().has(Field::SemiAxes) && p.fields().has(Field::Orientation);
  std::vector<char> mine;
  mine.reserve(p.n_owned() * sizeof(Record));
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    Record r{};
    r.id = p.id[i];
    r.ellipsoid = p.shape[i] == kEllipsoid ? 1 : 0;
    for (int d = 0; d < 3; ++d) r.x[d] = p.x[i][d];
    r.r = p.radius[i];
    if (r.ellipsoid && ell) {
      for (int d = 0; d < 3; ++d) r.axes[d] = p.semi_axes[i][d];
      const Quat& q = p.orientation[i];
      r.q[0] = q.w(), r.q[1] = q.x(), r.q[2] = q.y(), r.q[3] = q.z();
    }
    put(mine, r);
  }
  const auto all = Comm::world().gather(mine);
  std::vector<Record> recs;
  for (const auto& b : all)
    for (const char* q = b.data(); q < b.data() + b.size();) recs.push_back(take<Record>(q));
  std::sort(recs.begin(), recs.end(), [](const Record& a, const Record& b) { return a.id < b.id; });
  insert::SceneGrains g;
  for (const auto& r : recs) {
    const Vec3 x(r.x[0], r.x[1], r.x[2]);
    if (r.ellipsoid) {
      g.ell_x.push_back(x);
      g.ell_axes.emplace_back(r.axes[0], r.axes[1], r.axes[2]);
      g.ell_q.emplace_back(r.q[0], r.q[1], r.q[2], r.q[3]);
    } else {
      g.sphere_x.push_back(x);
      g.sphere_r.push_back(r.r);
    }
  }
  return g;
}

InsertionStage::InsertionStage(std::vector<InsertionConfig> entries, double dt, bool ellipsoid_fields)
    : entries_(std::move(entries)), totals_(entries_.size()), ellipsoid_fields_(ellipsoid_fields) {
  for (const auto& c : entries_) {
    Schedule sc;
    sc.first = std::max<std::int64_t>(1, std::llround(c.at / dt));
    sc.every = c.every > 0 ? std::max<std::int64_t>(1, std::llround(c.every / dt)) : 0;
    sc.last = c.until > 0 ? std::llround(c.until / dt) : std::numeric_limits<std::int64_t>::max();
    sc.times = c.times;
    sched_.push_back(sc);
  }
}

std::string InsertionStage::name() const {
  std::string n = "insert(";
  for (std::size_t e = 0; e < entries_.size(); ++e)
    n += (e ? ", " : "") + entries_[e].grains.name + ": " + method_name(entries_[e].method);
  return n + ")";
}

std::int64_t InsertionStage::event_at(std::size_t e, std::int64_t n) const {
  const auto& sc = sched_[e];
  if (n < sc.first || n > sc.last) return -1;
  if (n == sc.first) return 0;
  if (sc.every > 0 && (n - sc.first) % sc.every == 0) {
    const std::int64_t k = (n - sc.first) / sc.every;
    return sc.times > 0 && k >= sc.times ? -1 : k;
  }
  return -1;
}

void InsertionStage::run(Scene& s) {
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    const auto k = event_at(e, s.clock.step);
    if (k >= 0) insert_now(s, e, k);
  }
}

void InsertionStage::insert_now(Scene& s, std::size_t e, std::int64_t event) {
  const auto& c = entries_[e];
  const Comm& comm = Comm::world();
  const insert::SceneGrains scene_grains = gather_scene_grains(s);
  // Ids continue from the largest in use on any rank.
  std::int64_t max_id = -1, max_body = -1;
  for (std::size_t i = 0; i < s.particles.n_owned(); ++i) max_id = std::max(max_id, s.particles.id[i]);
  for (auto b : s.bodies.id) max_body = std::max(max_body, b);
  max_id = comm.max(max_id);
  max_body = comm.max(max_body);

  std::vector<char> bytes;
  std::string err;
  insert::InsertStats st;
  if (comm.root()) {
    try {
      const std::uint64_t seed = splitmix64(c.seed ^ splitmix64(static_cast<std::uint64_t>(event) * 1000003u + e));
      // One thread when results must not depend on the thread count.
      const int threads = s.deterministic ? 1 : omp_get_max_threads();
      const auto placed = insert::insert_grains(c, scene_grains, s.domain, s.walls, seed, threads, &st);
      for (const auto& g : placed) {
        const double rec[8] = {g.x[0], g.x[1], g.x[2], g.r, g.o.w(), g.o.x(), g.o.y(), g.o.z()};
        put(bytes, rec);
      }
    } catch (const std::exception& ex) {
      err = "insert '" + c.grains.name + "' (" + c.where + "): " + ex.what();
    }
  }
  if (comm.agree_error(err)) throw std::runtime_error(err);
  comm.broadcast(bytes);

  auto& p = s.particles;
  const std::size_t n_before = p.n_owned();
  const int me = comm.rank();
  const bool clump = c.grains.shape.kind == ShapeConfig::Kind::Clump;
  const std::int64_t balls = clump ? static_cast<std::int64_t>(c.grains.shape.clump->radii.size()) : 1;
  std::int64_t gid = max_id + 1, body = max_body + 1;
  bool cleared = false;
  for (const char* q = bytes.data(); q < bytes.data() + bytes.size();) {
    double rec[8];
    std::memcpy(rec, q, sizeof rec);
    q += sizeof rec;
    const Vec3 x(rec[0], rec[1], rec[2]);
    const Quat o(rec[4], rec[5], rec[6], rec[7]);
    const bool mine = !s.exchange || s.exchange->decomposition().owner(x) == me;
    if (mine) {
      if (!cleared) p.clear_ghosts();  // the next neighbour phase rebuilds them
      cleared = true;
      std::int64_t id = gid;
      add_grain(s, c.grains, x, rec[3], o, id, clump ? body : -1, ellipsoid_fields_, "inserted grain");
    }
    gid += balls;
    if (clump) ++body;
  }
  const std::size_t added = p.n_owned() - n_before;
  if (!s.exchange)
    s.neighbors.append_empty_rows(added);  // rows = particles: a checkpoint of this step restores
  else
    s.neighbors.invalidate();  // ghosts were cleared: the next step migrates and rebuilds

  auto& t = totals_[e];
  ++t.events;
  if (comm.root()) {
    t.last = st;
    t.requested += st.requested;
    t.placed += st.placed;
    t.trials += st.trials;
    t.seconds += st.seconds;
    if (st.placed < st.requested)
      std::cerr << c.where << ": insert '" << c.grains.name << "' at t = " << s.clock.time << " s: placed " << st.placed
                << " of " << st.requested << " grains ("
                << (c.budget > 0 && st.seconds >= c.budget ? "the time budget ran out"
                                                           : "no more free positions were found")
                << ")\n";
  }
}

std::string InsertionStage::summary_json() const {
  std::ostringstream o;
  o << "\"insertion\": [";
  for (std::size_t e = 0; e < entries_.size(); ++e) {
    const auto& t = totals_[e];
    o << (e ? ", " : "") << "{\"name\": \"" << entries_[e].grains.name << "\", \"method\": \""
      << method_name(entries_[e].method) << "\", \"events\": " << t.events << ", \"requested\": " << t.requested
      << ", \"placed\": " << t.placed << ", \"trials\": " << t.trials << ", \"seconds\": " << t.seconds << "}";
  }
  o << "]";
  return o.str();
}

void check_insertions(const SceneConfig& c) {
  for (const auto& ins : c.insertions) {
    const std::string at = ins.where + ": insert '" + ins.grains.name + "': ";
    if (c.integrator == Integrator::Arkode)
      throw SetupError(at + "grains cannot be inserted with time.integrator: arkode (its ODE state has a fixed "
                            "size); use the verlet integrator or remove insert");
    const auto& r = ins.region;
    for (int d = 0; d < 3; ++d)
      if (r.lo[d] < c.domain.lo[d] || r.hi[d] > c.domain.hi[d]) {
        std::ostringstream m;
        m << at << "the region reaches outside the domain along " << "xyz"[d] << " ([" << r.lo[d] << ", " << r.hi[d]
          << "] m, the domain is [" << c.domain.lo[d] << ", " << c.domain.hi[d] << "] m); keep it inside the domain";
        throw SetupError(m.str());
      }
    const double q = ins.grains.size.largest() * ins.grains.shape.bounding_factor;
    for (int d = 0; d < 3; ++d)
      if (r.hi[d] - r.lo[d] < 2 * q) {
        std::ostringstream m;
        m << at << "the region is " << r.hi[d] - r.lo[d] << " m wide along " << "xyz"[d]
          << ", less than the largest grain's bounding diameter " << 2 * q << " m; enlarge the region";
        throw SetupError(m.str());
      }
  }
}

}  // namespace grains::sim
