#include "io/output/mass_output.hpp"

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/output/csv_rows.hpp"
#include "sim/parallel/comm.hpp"
#include "sim/parallel/exchange.hpp"

namespace grains::io {

namespace fs = std::filesystem;

MassCount count_mass(const sim::Scene& s, const std::optional<std::pair<sim::Vec3, sim::Vec3>>& plane) {
  auto front = [&](const sim::Vec3& x) { return !plane || plane->second.dot(x - plane->first) > 0; };
  MassCount c;
  const auto& p = s.particles;
  const bool clumps = p.fields().has(sim::Field::Body);
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    if (clumps && p.body[i] >= 0) continue;  // counted with its body below
    if (!front(p.x[i])) continue;
    ++c.grains;
    c.mass += p.mass[i];
  }
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    if (!front(s.bodies.x[b])) continue;
    ++c.grains;
    c.mass += s.bodies.mass[b];
  }
  if (s.exchange) {  // each rank counted what it owns
    const auto& comm = s.exchange->comm();
    c.grains = static_cast<std::size_t>(comm.sum(static_cast<std::int64_t>(c.grains)));
    c.mass = comm.sum(c.mass);
  }
  return c;
}

MassOutput::MassOutput(fs::path dir, MassOutputConfig cfg, std::int64_t every_steps)
    : file_(std::move(dir) / "mass.csv"), cfg_(cfg), every_(every_steps) {}

std::string MassOutput::name() const {
  return std::string("output.mass(") + (cfg_.has_plane ? "front of a plane, " : "") +
         (every_ > 0 ? "every " + std::to_string(every_) + " steps" : std::string("first+last")) + ")";
}

void MassOutput::open() {
  if (out_.is_open() || !sim::Comm::world().root()) return;
  out_.open(file_, std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot write '" + file_.string() + "'");
  out_ << "step,time_s,grains,mass_kg,lost_particles\n";
}

void MassOutput::resume(const sim::Scene& s) {
  if (!sim::Comm::world().root()) {
    write_row(s);  // the reductions are collective
    return;
  }
  // Keep the header and the rows before the restart step, then write the
  // restored state's row and append after it.
  reopen_before(out_, file_, "step,time_s,grains,mass_kg,lost_particles", s.clock.step);
  write_row(s);
}

void MassOutput::write_row(const sim::Scene& s) {
  if (s.clock.step == last_step_) return;
  last_step_ = s.clock.step;
  std::optional<std::pair<sim::Vec3, sim::Vec3>> plane;
  if (cfg_.has_plane) plane.emplace(cfg_.point, cfg_.normal);
  const MassCount c = count_mass(s, plane);  // collective under MPI
  const std::int64_t lost = s.exchange ? s.exchange->comm().sum(s.lost_particles) : s.lost_particles;
  // Rank 0 writes; a failure is agreed on, so that every rank stops together.
  std::string err;
  try {
    open();
    if (sim::Comm::world().root()) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "%lld,%.10g,%zu,%.10g,%lld\n", static_cast<long long>(s.clock.step),
                    s.clock.time, c.grains, c.mass, static_cast<long long>(lost));
      out_ << buf;
      out_.flush();
      if (!out_) throw std::runtime_error("could not write '" + file_.string() + "'");
    }
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (sim::Comm::world().agree_error(err)) throw std::runtime_error(err);
}

void MassOutput::run(sim::Scene& s) {
  if (reads_state(s)) write_row(s);  // its cadence
}

void MassOutput::finish(sim::Scene& s) {
  write_row(s);
  if (out_.is_open()) out_.flush();
}

}  // namespace grains::io
