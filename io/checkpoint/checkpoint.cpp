#include "io/checkpoint/checkpoint.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <unistd.h>

#include "grains/version.hpp"
#include "io/checkpoint/h5_file.hpp"
#include "sim/parallel/comm.hpp"
#include "sim/parallel/id_blocks.hpp"

namespace grains::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kFormat = "grains checkpoint";
// 2: a mesh wall's block of wall_contact_normal holds its mask first, then
// the slots' normals (version 1: the normals, then the mask).
constexpr const char* kFormatVersion = "2";
constexpr const char* kHistoryUnits = "m (tangential), N m (rolling)";

void fsync_path(const fs::path& p, bool directory) {
  const int fd = ::open(p.c_str(), directory ? O_RDONLY | O_DIRECTORY : O_RDONLY);
  if (fd < 0) throw CheckpointError("cannot open '" + p.string() + "' to sync it: " + std::strerror(errno));
  const int rc = ::fsync(fd);
  const int e = errno;
  ::close(fd);
  if (rc != 0) throw CheckpointError("fsync of '" + p.string() + "' failed: " + std::strerror(e));
}

// The owned particles of `p` as rows [offset, offset + n_owned) of `total`
// (a serial file: offset 0, total n_owned).
void write_particles(const h5::File& f, sim::ParticleStore& p, std::size_t offset, std::size_t total) {
  const std::size_t n = p.n_owned();
  f.group("/particles");
  f.attribute("/particles", "count", std::to_string(total));
  p.visit_fields([&](const char* name, const char* unit, auto& vec, int width) {
    using T = typename std::decay_t<decltype(vec)>::value_type;
    const std::string ds = std::string("/particles/") + name;
    const std::size_t cols = static_cast<std::size_t>(h5::Elem<T>::n) * static_cast<std::size_t>(width);
    f.write_rows(ds, h5::Elem<T>::type(), vec.data(), n, cols, offset, total, unit);  // owned rows only
    if constexpr (std::is_same_v<T, sim::Quat>) f.attribute(ds, "components", "x y z w");
  });
}

// Rigid clumps (scenes with clumps only): every per-body array of BodyStore.
void write_bodies(const h5::File& f, sim::BodyStore& b, std::size_t offset, std::size_t total) {
  f.group("/bodies");
  f.attribute("/bodies", "count", std::to_string(total));
  b.visit_fields([&](const char* name, const char* unit, auto& vec) {
    using T = typename std::decay_t<decltype(vec)>::value_type;
    const std::string ds = std::string("/bodies/") + name;
    f.write_vector_rows(ds, vec, 1, offset, total, unit);
    if constexpr (std::is_same_v<T, sim::Quat>) f.attribute(ds, "components", "x y z w");
  });
}

// Each wall's near list, by the walls' index across kinds.
// Each wall's near list, by the walls' index across kinds, and what a kind
// keeps per near particle (a mesh wall: its near triangles) when it has any.
void write_wall_near(const h5::File& f, const std::vector<std::vector<std::uint32_t>>& near,
                     const std::vector<sim::NearItems>& items = {}) {
  f.group("/neighbor/wall_near");
  for (std::size_t w = 0; w < near.size(); ++w)
    f.write_vector("/neighbor/wall_near/" + std::to_string(w), near[w], 1, "");
  bool any = false;
  for (const auto& it : items) any = any || !it.items.empty();
  if (!any) return;
  f.group("/neighbor/wall_items");
  for (std::size_t w = 0; w < items.size(); ++w) {
    if (items[w].items.empty()) continue;
    f.write_vector("/neighbor/wall_items/" + std::to_string(w) + "_start", items[w].start, 1, "");
    f.write_vector("/neighbor/wall_items/" + std::to_string(w), items[w].items, 1, "");
  }
}

void write_neighbors(const h5::File& f, const sim::NeighborList& nl) {
  f.group("/neighbor");
  const auto b = nl.build_state();
  f.write_vector("/neighbor/row_start", nl.row_start, 1, "");
  f.write_vector("/neighbor/partner", nl.partner, 1, "");
  const int H = nl.history_size();
  f.write_raw("/neighbor/history", H5T_NATIVE_DOUBLE, nl.history.data(), H > 0 ? nl.history.size() / H : 0,
              static_cast<std::size_t>(std::max(H, 1)), kHistoryUnits);
  f.write_scalar("/neighbor/history_size", static_cast<std::int32_t>(H), "");
  f.write_scalar("/neighbor/skin", nl.skin(), "m");
  if (nl.skin_fraction() > 0) f.write_scalar("/neighbor/skin_per_grain", nl.skin_fraction(), "");
  f.write_vector("/neighbor/build_position", b.x, 1, "m");
  f.write_vector("/neighbor/build_row_id", b.row_id, 1, "");
  f.write_scalar("/neighbor/build_time", b.time, "s");
  f.write_scalar("/neighbor/builds", static_cast<std::int64_t>(b.builds), "");
  f.write_scalar("/neighbor/build_growth", b.growth, "m");
  write_wall_near(f, nl.wall_near, nl.wall_items);
}

// The dataset of one kind's positions (e.g. /walls/plane_point, /walls/cylinder_base).
template <class K>
std::string wall_position_dataset() {
  return std::string("/walls/") + K::kind + "_" + K::position_name;
}

// A mesh wall's motion in a checkpoint (write_walls): rebased, base time,
// base offset (3), base angle, base vibration (3), angle, velocity (3),
// angular velocity, vibration amplitude (3) and frequency, start, ramp,
// axis (3), axis point (3).
constexpr int kMeshMotionWidth = 26;

// Each kind's moving reference points and velocities: what a restart needs
// besides the case (the walls' shape comes from the case).
void write_walls(const h5::File& f, const sim::Walls& walls) {
  f.group("/walls");
  sim::for_each_type(sim::WallKinds{}, [&]<class K>() {
    std::vector<sim::Vec3> pos, vel;
    for (const auto& w : walls.of<K>()) pos.push_back(w.position()), vel.push_back(w.velocity);
    f.write_vector(wall_position_dataset<K>(), pos, 1, "m");
    f.write_vector(std::string("/walls/") + K::kind + "_velocity", vel, 1, "m/s");
    if constexpr (K::controllable) {
      // Controlled walls: the speed of the next step, the travel so far, the speed bound.
      bool any = false;
      std::vector<double> ctl;
      for (const auto& w : walls.of<K>()) {
        any = any || w.control.active();
        ctl.insert(ctl.end(), {w.control.speed, w.control.travel, w.control.max_speed});
      }
      if (any) f.write_vector(std::string("/walls/") + K::kind + "_control", ctl, 3, "");
    }
    if constexpr (requires(K k) { k.motion_time; k.surface->triangles(); }) {
      // A kind with its own motion clock (its pose is a function of it), and
      // the size of its surface (a restart must use the same mesh).
      std::vector<double> clock;
      std::vector<std::int64_t> tris;
      for (const auto& w : walls.of<K>()) clock.push_back(w.motion_time), tris.push_back(static_cast<std::int64_t>(w.surface->triangles()));
      f.write_vector(std::string("/walls/") + K::kind + "_motion_time", clock, 1, "s");
      f.write_vector(std::string("/walls/") + K::kind + "_triangles", tris, 1, "");
    }
    if constexpr (requires(K k) { k.rebase(0.0, sim::Vec3{}, 0.0); }) {
      // The motion the pose came from (a script may have changed it): a
      // restart with the same motion continues bitwise, one with another
      // motion (an edited case) continues from this pose (read_walls).
      std::vector<double> m;
      for (const auto& w : walls.of<K>()) {
        m.insert(m.end(), {w.rebased ? 1.0 : 0.0, w.base_time});
        m.insert(m.end(), w.base_offset.data(), w.base_offset.data() + 3);
        m.push_back(w.base_angle);
        m.insert(m.end(), w.base_vibration.data(), w.base_vibration.data() + 3);
        m.push_back(w.angle);
        m.insert(m.end(), w.velocity.data(), w.velocity.data() + 3);
        m.push_back(w.angular_velocity);
        m.insert(m.end(), w.vibration_amplitude.data(), w.vibration_amplitude.data() + 3);
        m.insert(m.end(), {w.vibration_frequency, w.start, w.ramp});
        m.insert(m.end(), w.axis.data(), w.axis.data() + 3);
        m.insert(m.end(), w.axis_point.data(), w.axis_point.data() + 3);
      }
      f.write_vector(std::string("/walls/") + K::kind + "_motion", m, kMeshMotionWidth, "");
    }
  });
}

// Hidden, so that listings never see it.
fs::path temporary_name(const fs::path& file) {
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::string tmp_name(1, '.');
  tmp_name.append(file.filename().string()).append(".tmp");
  return dir / tmp_name;
}

void write_head(const h5::File& f, const sim::Clock& clock, const CheckpointExtras& x) {
  f.attribute("/", "format", kFormat);
  f.attribute("/", "format_version", kFormatVersion);
  f.attribute("/", "grains_version", kVersion);
  f.group("/clock");
  f.write_scalar("/clock/time", clock.time, "s");
  f.write_scalar("/clock/dt", clock.dt, "s");
  f.write_scalar("/clock/end_time", clock.end_time, "s");
  f.write_scalar("/clock/step", clock.step, "");
  f.write_scalar("/clock/n_steps", clock.n_steps, "");
  f.group("/case");
  f.write_string("/case/path", x.case_path);
  f.write_string("/case/text", x.case_text);
  f.write_string("/case/effective", x.case_effective);
}

// A pressure-servoed Lees–Edwards cell (domain.shear.pressure): its height
// along the gradient and the piecewise offset of its sheared images, which
// the case no longer gives.
void write_domain(const h5::File& f, const sim::Domain& d) {
  if (!d.shear.servo()) return;
  f.group("/domain");
  const int g = d.shear.gradient;
  f.write_vector("/domain/shear_cell", std::vector<double>{d.hi[g] - d.lo[g], d.shear.base_offset, d.shear.base_time},
                 3, "m, m, s");
}

// The radius-growth servo (Scene::growth): what it measured last, the rate
// in force and the phase of the schedule.
void write_growth(const h5::File& f, const sim::GrowthServo& g) {
  f.group("/growth");
  f.write_scalar("/growth/started", static_cast<std::int32_t>(g.started), "");
  f.write_scalar("/growth/capped", static_cast<std::int32_t>(g.capped), "");
  f.write_scalar("/growth/last_measure", g.last_measure, "step");
  f.write_scalar("/growth/overlap", g.overlap, "");
  f.write_scalar("/growth/rate", g.rate, "1/s");
  f.write_scalar("/growth/phase_rate", g.phase_rate, "1/s");
  f.write_scalar("/growth/phase_target", g.phase_target, "");
}

void write_tail(const h5::File& f, const sim::Walls& walls, const sim::GrowthServo& growth, std::int64_t lost,
                const CheckpointExtras& x) {
  write_walls(f, walls);
  write_growth(f, growth);
  f.group("/scene");
  f.write_scalar("/scene/lost_particles", lost, "");
  f.group("/output");
  f.write_vector("/output/vtk_frame_times", x.frame_times, 1, "s");
  f.write_vector("/output/vtk_frame_steps", x.frame_steps, 1, "");
  if (!x.cuts[0].empty()) {
    f.group("/parallel");
    f.write_vector("/parallel/cuts_x", x.cuts[0], 1, "m");
    f.write_vector("/parallel/cuts_y", x.cuts[1], 1, "m");
    f.write_vector("/parallel/cuts_z", x.cuts[2], 1, "m");
  }
  f.attribute("/", "complete", "yes");  // last: a reader refuses a file without it
}

// The renamed file's folder entry, made durable.
void publish(const fs::path& tmp, const fs::path& file) {
  std::error_code ec;
  fs::rename(tmp, file, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw CheckpointError("could not write checkpoint '" + file.string() + "': rename failed: " + ec.message());
  }
  fsync_path(file.has_parent_path() ? file.parent_path() : fs::path("."), true);
}

}  // namespace

void write_checkpoint(const fs::path& file, sim::Scene& s, const CheckpointExtras& x) {
  const fs::path tmp = temporary_name(file);
  try {
    auto f = h5::File::create(tmp.string());
    write_head(f, s.clock, x);
    write_domain(f, s.domain);
    write_particles(f, s.particles, 0, s.particles.n_owned());
    if (s.particles.fields().has(sim::Field::Body)) write_bodies(f, s.bodies, 0, s.bodies.size());
    write_neighbors(f, s.neighbors);
    write_tail(f, s.walls, s.growth, s.lost_particles, x);
    f.close();
    fsync_path(tmp, false);
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove(tmp, ec);  // do not leave a partial file behind (it may be what filled the disk)
    throw CheckpointError(std::string("could not write checkpoint '") + file.string() + "': " + e.what());
  }
  publish(tmp, file);
}

bool parallel_checkpoint_io() {
  if (!h5::File::can_write_parallel()) return false;
  const char* v = std::getenv("GRAINS_CHECKPOINT_IO");
  const std::string how = v ? v : "";
  if (how.empty() || how == "mpiio") return true;
  if (how == "gather") return false;
  throw CheckpointError("GRAINS_CHECKPOINT_IO='" + how + "': valid values are mpiio (the default under MPI) and gather");
}

void write_checkpoint_parallel(const fs::path& file, sim::Scene& s, sim::IdBlock& b, const CheckpointExtras& x) {
  const auto& comm = sim::Comm::world();
  const fs::path tmp = temporary_name(file);
  std::string err;
  try {
    // Every call below is made by every rank in the same order; errors are
    // agreed on at check() and close(), so a failure throws on all ranks at
    // the same point and the file is closed (collectively) by all of them.
    auto f = h5::File::create_parallel(tmp.string());
    write_head(f, s.clock, x);
    write_domain(f, s.domain);
    auto& q = b.particles;
    write_particles(f, q, b.particle_offset, b.particle_total);
    if (s.particles.fields().has(sim::Field::Body))
      write_bodies(f, b.bodies, b.body_offset, b.body_total);
    f.check();  // the bulk of the data: stop here on every rank if any failed
    // The contact histories as CSR rows in global-id order (as gather_scene
    // makes them): no build positions, so the continuing run rebuilds at
    // its first step and carries the histories over by global ids.
    f.group("/neighbor");
    const int H = s.neighbors.history_size();
    const bool last = comm.rank() == comm.size() - 1;  // writes the closing row_start (the entry count)
    f.write_rows("/neighbor/row_start", H5T_NATIVE_UINT32, b.row_start.data(), q.n_owned() + (last ? 1 : 0), 1,
                 b.particle_offset, b.particle_total + 1, "");
    f.write_vector_rows("/neighbor/partner", b.partner, 1, b.entry_offset, b.entry_total, "");
    f.write_rows("/neighbor/history", H5T_NATIVE_DOUBLE, b.history.data(), H > 0 ? b.partner.size() : 0,
                 static_cast<std::size_t>(std::max(H, 1)), b.entry_offset, H > 0 ? b.entry_total : 0, kHistoryUnits);
    f.write_scalar("/neighbor/history_size", static_cast<std::int32_t>(H), "");
    f.write_scalar("/neighbor/skin", s.neighbors.skin(), "m");
    if (s.neighbors.skin_fraction() > 0)
      f.write_scalar("/neighbor/skin_per_grain", s.neighbors.skin_fraction(), "");
    f.write_vector("/neighbor/build_position", std::vector<sim::Vec3>{}, 1, "m");
    f.write_vector_rows("/neighbor/build_row_id", q.id, 1, b.particle_offset, b.particle_total, "");
    f.write_scalar("/neighbor/build_time", s.clock.time, "s");
    f.write_scalar("/neighbor/builds", static_cast<std::int64_t>(s.neighbors.stats().builds), "");
    f.write_scalar("/neighbor/build_growth", 0.0, "m");
    write_wall_near(f, std::vector<std::vector<std::uint32_t>>(s.walls.count()));
    write_tail(f, s.walls, s.growth, b.lost_particles, x);
    f.close();  // H5Fflush (MPI_File_sync on every rank), then the collective close
  } catch (const std::exception& e) {
    err = e.what();  // the same on every rank
  }
  if (!err.empty()) {
    std::error_code ec;
    if (comm.root()) fs::remove(tmp, ec);  // no partial file left behind
    throw CheckpointError("could not write checkpoint '" + file.string() + "': " + err);
  }
  // All ranks have closed the file; rank 0 makes it durable and publishes it.
  if (comm.root()) {
    try {
      fsync_path(tmp, false);
      publish(tmp, file);
    } catch (const std::exception& e) {
      std::error_code ec;
      fs::remove(tmp, ec);
      err = e.what();
    }
  }
  if (comm.agree_error(err)) throw CheckpointError(err);
}

namespace {

void check_format(const h5::File& f) {
  if (f.read_attribute("/", "format") != kFormat) throw CheckpointError(f.path() + ": not a grains checkpoint");
  const auto v = f.read_attribute("/", "format_version");
  if (v != kFormatVersion)
    throw CheckpointError(f.path() + ": checkpoint format version " + v + ", this grains reads version " +
                          kFormatVersion);
  if (f.read_attribute("/", "complete") != "yes") throw CheckpointError(f.path() + ": incomplete checkpoint");
}

std::size_t particle_count(const h5::File& f) { return std::stoull(f.read_attribute("/particles", "count")); }

// Returns the fields the checkpoint lacked (FieldInfo::restart_fresh, allowed
// by check_compatible), which start as a new particle's.
std::vector<std::string> read_particles(const h5::File& f, sim::ParticleStore& p) {
  const std::size_t n = particle_count(f);
  // Resize through the public interface: empty the store, then add n
  // placeholders, which allocates every configured field; all are overwritten.
  p.remove_if(std::vector<char>(p.n_owned(), 1));
  for (std::size_t i = 0; i < n; ++i) p.add(0, sim::Vec3::Zero(), sim::Vec3::Zero(), 1.0, 1.0, 0, 0);
  std::vector<std::string> seen;
  p.visit_fields([&](const char* name, const char*, auto& vec, int width) {
    const std::string ds = std::string("/particles/") + name;
    if (!f.exists(ds)) return;  // check_compatible allowed it to start fresh
    f.read_vector(ds, vec, n, width);
    seen.emplace_back(name);
  });
  std::vector<std::string> fresh;
  p.declare_fields([&](const sim::ParticleStore::FieldInfo& fi, auto member, auto make) {
    if (std::find(seen.begin(), seen.end(), fi.name) != seen.end()) return;
    auto& vec = p.*member;
    const auto w = static_cast<std::size_t>(fi.width);
    for (std::size_t i = 0; i < n; ++i) {
      const sim::ParticleStore::NewParticle q{p.id[i], p.x[i], p.v[i], p.radius[i], p.mass[i], p.material[i], p.shape[i]};
      const auto value = make(q);
      for (std::size_t c = 0; c < w; ++c) vec[i * w + c] = value;
    }
    fresh.emplace_back(fi.name);
  });
  for (const auto& c : f.children("/particles"))
    if (std::find(seen.begin(), seen.end(), c) == seen.end())
      throw CheckpointError(f.path() + ": has particle field '" + c +
                            "', which this case does not use: the checkpoint was written for a different case");
  return fresh;
}

void read_bodies(const h5::File& f, sim::Scene& s) {
  auto& b = s.bodies;
  if (!f.exists("/bodies"))
    throw CheckpointError(f.path() + ": has no clump bodies, which this case needs: the checkpoint was written for a "
                          "different case");
  const std::size_t n = std::stoull(f.read_attribute("/bodies", "count"));
  b.visit_fields([&](const char* name, const char*, auto& vec) {
    const std::string ds = std::string("/bodies/") + name;
    if (!f.exists(ds)) throw CheckpointError(f.path() + ": clump body field '" + name + "' is missing (corrupt checkpoint)");
    f.read_vector(ds, vec, n, 1);
  });
  b.rebuild_index();
  // Every ball must find its body.
  const auto& p = s.particles;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if (p.body[i] >= 0 && b.index_of(p.body[i]) < 0)
      throw CheckpointError(f.path() + ": particle id " + std::to_string(p.id[i]) + " belongs to clump " +
                            std::to_string(p.body[i]) + ", which the checkpoint does not hold (corrupt checkpoint)");
}

void read_neighbors(const h5::File& f, sim::Scene& s) {
  auto& nl = s.neighbors;
  const std::size_t n = s.particles.n_owned();
  const int H = nl.history_size();  // checked against the file in check_compatible
  f.read_vector("/neighbor/row_start", nl.row_start, f.shape("/neighbor/row_start").first, 1);
  const std::size_t m = f.shape("/neighbor/partner").first;
  f.read_vector("/neighbor/partner", nl.partner, m, 1);
  if (f.read_scalar<std::int32_t>("/neighbor/history_size") == 0) {
    nl.history.assign(m * static_cast<std::size_t>(H), 0.0);  // none kept: every contact starts afresh
  } else {
    nl.history.resize(m * static_cast<std::size_t>(H));
    f.read_raw("/neighbor/history", H5T_NATIVE_DOUBLE, nl.history.data(), H > 0 ? m : 0,
               static_cast<std::size_t>(std::max(H, 1)));
  }
  bool ok = nl.row_start.size() == n + 1 && nl.row_start.front() == 0 && nl.row_start.back() == m;
  for (std::size_t i = 0; ok && i < n; ++i) ok = nl.row_start[i] <= nl.row_start[i + 1];
  for (std::size_t k = 0; ok && k < m; ++k) ok = nl.partner[k] < n;
  if (!ok) throw CheckpointError(f.path() + ": the neighbour list does not fit the particles (corrupt checkpoint)");
  sim::NeighborList::BuildState b;
  f.read_vector("/neighbor/build_position", b.x, f.shape("/neighbor/build_position").first, 1);
  f.read_vector("/neighbor/build_row_id", b.row_id, f.shape("/neighbor/build_row_id").first, 1);
  b.time = f.read_scalar<double>("/neighbor/build_time");
  b.builds = static_cast<long>(f.read_scalar<std::int64_t>("/neighbor/builds"));
  // Radius growth since the build (absent from checkpoints before 2026-11-21:
  // a growing run then rebuilds its list at its first step).
  if (f.exists("/neighbor/build_growth")) b.growth = f.read_scalar<double>("/neighbor/build_growth");
  // Near lists by the walls' index across kinds; checkpoints before
  // 2026-11-26 kept planes' and cylinders' lists in groups of their own.
  nl.wall_near.assign(s.walls.count(), {});
  std::size_t w = 0;
  auto near = [&](const std::string& group, std::size_t count) {
    for (std::size_t k = 0; k < count; ++k, ++w) {
      const std::string ds = group + "/" + std::to_string(k);
      f.read_vector(ds, nl.wall_near[w], f.shape(ds).first, 1);
      for (auto i : nl.wall_near[w])
        if (i >= n) throw CheckpointError(f.path() + ": wall near list out of range (corrupt checkpoint)");
    }
  };
  nl.wall_items.assign(s.walls.count(), {});
  if (f.exists("/neighbor/wall_near")) {
    near("/neighbor/wall_near", s.walls.count());
    s.walls.for_each([&](const auto& wall, std::size_t k) {
      const std::string ds = "/neighbor/wall_items/" + std::to_string(k);
      if (!f.exists(ds)) {  // a kind without items writes none
        if (std::decay_t<decltype(wall)>::near_items && !nl.wall_near[k].empty())
          throw CheckpointError(f.path() + ": wall " + std::to_string(k) + " (" + wall.name +
                                ") has a near list but no near items, " + ds + " (corrupt checkpoint)");
        return;
      }
      auto& it = nl.wall_items[k];
      f.read_vector(ds + "_start", it.start, f.shape(ds + "_start").first, 1);
      f.read_vector(ds, it.items, f.shape(ds).first, 1);
      bool ok = it.start.size() == nl.wall_near[k].size() + 1 && it.start.front() == 0 &&
                it.start.back() == it.items.size() && std::is_sorted(it.start.begin(), it.start.end());
      if (!ok) throw CheckpointError(f.path() + ": wall " + std::to_string(k) + "'s near items do not fit its near list (corrupt checkpoint)");
    });
  } else {
    near("/neighbor/plane_near", s.walls.of<sim::PlaneWall>().size());
    near("/neighbor/cylinder_near", s.walls.of<sim::CylinderWall>().size());
  }
  nl.restore(s.particles, std::move(b));
}

void read_domain(const h5::File& f, const std::string& file, sim::Domain& d) {
  if (!d.shear.servo()) return;
  if (!f.exists("/domain/shear_cell"))
    throw CheckpointError(file + ": has no /domain/shear_cell, which the pressure of domain.shear needs: the "
                                 "checkpoint was written for a cell of fixed volume");
  std::vector<double> v;
  f.read_vector("/domain/shear_cell", v, 1, 3);
  if (v.size() != 3 || !(v[0] > 0)) throw CheckpointError(file + ": /domain/shear_cell is corrupt");
  const int g = d.shear.gradient;
  d.hi[g] = d.lo[g] + v[0];
  d.shear.base_offset = v[1];
  d.shear.base_time = v[2];
}

void read_growth(const h5::File& f, sim::GrowthServo& g) {
  g = {};  // checkpoints before 2026-11-21 have none: the servo measures at the first step
  if (!f.exists("/growth/started")) return;
  g.started = f.read_scalar<std::int32_t>("/growth/started") != 0;
  g.capped = f.read_scalar<std::int32_t>("/growth/capped") != 0;
  g.last_measure = f.read_scalar<std::int64_t>("/growth/last_measure");
  g.overlap = f.read_scalar<double>("/growth/overlap");
  g.rate = f.read_scalar<double>("/growth/rate");
  g.phase_rate = f.read_scalar<double>("/growth/phase_rate");
  g.phase_target = f.read_scalar<double>("/growth/phase_target");
}

// A mesh wall's motion from its checkpoint row (write_walls) at motion time
// t. The same motion as the case's: as it was, so the run continues
// bitwise. Another (the case was edited, or a script had changed it): the
// case's motion from the checkpoint's pose on. The axis cannot change.
template <class W>
void restore_motion(const h5::File& f, W& w, const double* r, double t) {
  const sim::Vec3 axis(r[20], r[21], r[22]), axis_point(r[23], r[24], r[25]);
  if (axis != w.axis || axis_point != w.axis_point)
    throw CheckpointError(f.path() + ": mesh wall '" + w.name + "' turned about another axis (axis, axis_point); a " +
                          "restart keeps a mesh wall's rotation axis");
  const bool same = w.velocity == sim::Vec3(r[10], r[11], r[12]) && w.angular_velocity == r[13] &&
                    w.vibration_amplitude == sim::Vec3(r[14], r[15], r[16]) && w.vibration_frequency == r[17] &&
                    w.start == r[18] && w.ramp == r[19];
  if (same) {
    w.rebased = r[0] != 0, w.base_time = r[1];
    w.base_offset = sim::Vec3(r[2], r[3], r[4]), w.base_angle = r[5];
    w.base_vibration = sim::Vec3(r[6], r[7], r[8]);
    w.place(t);
    return;
  }
  // The offset read is the pose's, with the controlled travel on top (place() adds it).
  sim::Vec3 offset = w.position();
  if (w.control.active()) offset -= w.control.travel * w.control.direction;
  w.rebase(t, offset, r[9]);
}

void read_walls(const h5::File& f, sim::Walls& walls) {
  sim::for_each_type(sim::WallKinds{}, [&]<class K>() {
    auto& ws = walls.of<K>();  // the count is checked in check_compatible
    std::vector<sim::Vec3> pos;
    if (!ws.empty()) f.read_vector(wall_position_dataset<K>(), pos, ws.size(), 1);
    for (std::size_t w = 0; w < ws.size(); ++w) ws[w].position() = pos[w];
    if constexpr (K::controllable) {
      bool any = false;
      for (const auto& w : ws) any = any || w.control.active();
      const std::string name = std::string("/walls/") + K::kind + "_control";
      if (any && !f.exists(name))
        throw std::runtime_error(f.path() + ": has no state of controlled walls (" + name +
                                 "); it was written by a case without walls[].control");
      if (any) {
        std::vector<double> ctl;
        f.read_vector(name, ctl, ws.size(), 3);
        for (std::size_t w = 0; w < ws.size(); ++w) {
          auto& c = ws[w].control;
          if (!c.active()) continue;
          c.speed = ctl[3 * w], c.travel = ctl[3 * w + 1], c.max_speed = ctl[3 * w + 2];
          if constexpr (!requires { ws[w].motion_time; }) ws[w].velocity = c.speed * c.direction;
        }
      }
    }
    if constexpr (requires(K k) { k.motion_time; k.place(0.0); }) {
      std::vector<double> clock;
      if (!ws.empty()) f.read_vector(std::string("/walls/") + K::kind + "_motion_time", clock, ws.size(), 1);
      // Checkpoints before 2026-11-27 have no motion: the case's, from motion time 0.
      const std::string motion = std::string("/walls/") + K::kind + "_motion";
      std::vector<double> m;
      if (!ws.empty() && f.exists(motion)) f.read_vector(motion, m, ws.size(), kMeshMotionWidth);
      for (std::size_t w = 0; w < ws.size(); ++w) {
        if constexpr (requires(K k) { k.rebase(0.0, sim::Vec3{}, 0.0); })
          if (!m.empty()) {
            restore_motion(f, ws[w], &m[kMeshMotionWidth * w], clock[w]);
            continue;
          }
        ws[w].place(clock[w]);
      }
    }
  });
}

// Everything that must match between the checkpoint and the scene built from
// the case, checked before the scene is touched.
void check_compatible(const h5::File& f, sim::Scene& s) {
  const std::string& file = f.path();
  const double dt = f.read_scalar<double>("/clock/dt");
  if (dt != s.clock.dt)
    throw CheckpointError(file + ": written with time step dt = " + std::to_string(dt) + " s, the case gives dt = " +
                          std::to_string(s.clock.dt) + " s; a restart keeps the time step");
  const auto step = f.read_scalar<std::int64_t>("/clock/step");
  if (step > s.clock.n_steps)
    throw CheckpointError(file + ": written at step " + std::to_string(step) + ", after the case's end (" +
                          std::to_string(s.clock.n_steps) + " steps); raise time.end to continue from it");
  const int H = f.read_scalar<std::int32_t>("/neighbor/history_size");
  // A stage without any history-keeping law (frictionless grains, say) may be
  // continued by one with such laws: its contacts then start with zero
  // history, as contacts that have just formed (read_neighbors).
  if (H != s.neighbors.history_size() && H != 0)
    throw CheckpointError(file + ": contact history of " + std::to_string(H) + " doubles per contact, the case's " +
                          "contact law keeps " + std::to_string(s.neighbors.history_size()) +
                          ": the checkpoint was written for different contact-law slots");
  if (f.read_scalar<double>("/neighbor/skin") != s.neighbors.skin())
    throw CheckpointError(file + ": the neighbour skin differs from the case's (neighbor.skin must not change)");
  const double per_grain = f.exists("/neighbor/skin_per_grain") ? f.read_scalar<double>("/neighbor/skin_per_grain") : 0;
  if (per_grain != s.neighbors.skin_fraction())
    throw CheckpointError(file + ": written with neighbor.skin_per_grain " + (per_grain > 0 ? "true" : "false") +
                          ", the case has " + (per_grain > 0 ? "false" : "true") + " (it must not change)");
  sim::for_each_type(sim::WallKinds{}, [&]<class K>() {
    const std::string ds = wall_position_dataset<K>();
    const std::size_t have = f.exists(ds) ? f.shape(ds).first : 0, want = s.walls.of<K>().size();
    if (have != want)
      throw CheckpointError(file + ": " + std::to_string(have) + " " + K::kind + " wall(s), the case has " +
                            std::to_string(want));
    if constexpr (requires(K k) { k.surface->triangles(); }) {
      const std::string tds = std::string("/walls/") + K::kind + "_triangles";
      std::vector<std::int64_t> tris;
      if (want > 0) {
        if (!f.exists(tds)) throw CheckpointError(file + ": has no " + tds + " (corrupt checkpoint)");
        f.read_vector(tds, tris, want, 1);
      }
      for (std::size_t w = 0; w < want; ++w) {
        const auto& wall = s.walls.of<K>()[w];
        if (tris[w] != static_cast<std::int64_t>(wall.surface->triangles()))
          throw CheckpointError(file + ": " + K::kind + " wall '" + wall.name + "' had " + std::to_string(tris[w]) +
                                " triangles, its file '" + wall.file + "' now has " +
                                std::to_string(wall.surface->triangles()) + ": the mesh changed since the checkpoint");
      }
    }
  });
  const std::size_t n = particle_count(f);
  std::vector<std::string> fresh;
  s.particles.declare_fields([&](const sim::ParticleStore::FieldInfo& fi, auto member, auto) {
    using T = typename std::decay_t<decltype(s.particles.*member)>::value_type;
    const std::string name = fi.name;
    const int width = fi.width;
    const std::string ds = "/particles/" + name;
    if (!f.exists(ds)) {
      if (!fi.restart_fresh)
        throw CheckpointError(file + ": has no particle field '" + name +
                              "', which this case needs: the checkpoint was written for a different case");
      fresh.push_back(name);
      return;
    }
    const auto shape = f.shape(ds);
    const std::size_t cols = static_cast<std::size_t>(h5::Elem<T>::n) * static_cast<std::size_t>(width);
    if (shape.first != n || shape.second != cols)
      throw CheckpointError(file + ": particle field '" + name + "' has " + std::to_string(shape.second) +
                            " values per particle, this case needs " + std::to_string(cols) +
                            ": the checkpoint was written for a different case (walls or contact-law slots)");
  });
  // A new particle's value of those fields is a sphere's (a solid sphere's
  // inertia); other shapes always carry them.
  if (!fresh.empty()) {
    std::vector<std::int32_t> shape;
    f.read_vector("/particles/shape", shape, n, 1);
    if (std::any_of(shape.begin(), shape.end(), [](std::int32_t k) { return k != sim::kSphere; }))
      throw CheckpointError(file + ": has no particle field '" + fresh.front() +
                            "' and holds non-spherical particles, which always have it: the checkpoint was written "
                            "for a different case");
  }
}

}  // namespace

CheckpointExtras read_checkpoint(const fs::path& file, sim::Scene& s) {
  try {
    const auto f = h5::File::open_read(file.string());
    check_format(f);
    check_compatible(f, s);
    const auto step = f.read_scalar<std::int64_t>("/clock/step");
    read_walls(f, s.walls);
    read_domain(f, file.string(), s.domain);
    auto fresh = read_particles(f, s.particles);
    if (s.particles.fields().has(sim::Field::Body)) read_bodies(f, s);
    read_neighbors(f, s);
    s.clock.step = step;
    s.clock.time = f.read_scalar<double>("/clock/time");
    s.lost_particles = f.read_scalar<std::int64_t>("/scene/lost_particles");
    read_growth(f, s.growth);
    CheckpointExtras x;
    x.fresh_fields = std::move(fresh);
    x.case_path = f.read_string("/case/path");
    x.case_text = f.read_string("/case/text");
    x.case_effective = f.read_string("/case/effective");
    f.read_vector("/output/vtk_frame_times", x.frame_times, f.shape("/output/vtk_frame_times").first, 1);
    f.read_vector("/output/vtk_frame_steps", x.frame_steps, f.shape("/output/vtk_frame_steps").first, 1);
    if (f.exists("/parallel/cuts_x")) {
      const char* names[3] = {"/parallel/cuts_x", "/parallel/cuts_y", "/parallel/cuts_z"};
      for (int d = 0; d < 3; ++d) f.read_vector(names[d], x.cuts[d], f.shape(names[d]).first, 1);
    }
    return x;
  } catch (const h5::H5Error& e) {
    throw CheckpointError(e.what());
  }
}

CheckpointInfo checkpoint_info(const fs::path& file) {
  try {
    const auto f = h5::File::open_read(file.string());
    check_format(f);
    return {f.read_scalar<std::int64_t>("/clock/step"), f.read_scalar<double>("/clock/time"), particle_count(f)};
  } catch (const h5::H5Error& e) {
    throw CheckpointError(e.what());
  }
}

}  // namespace grains::io
