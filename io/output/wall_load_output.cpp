#include "io/output/wall_load_output.hpp"

#include <sstream>
#include <stdexcept>

#include "io/output/csv_rows.hpp"
#include "sim/parallel/comm.hpp"
#include "sim/parallel/exchange.hpp"

namespace grains::io {

namespace fs = std::filesystem;

namespace {
const char* kHeader =
    "step,time_s,wall,name,kind,fx_N,fy_N,fz_N,tx_Nm,ty_Nm,tz_Nm,axial_torque_Nm,px_m,py_m,pz_m,speed_mps,area_m2,"
    "stress_Pa";
}

WallLoadOutput::WallLoadOutput(fs::path dir, WallLoadConfig cfg, std::int64_t every_steps)
    : file_(std::move(dir) / "wall_loads.csv"), cfg_(cfg), every_(every_steps) {}

std::string WallLoadOutput::name() const {
  return "output.wall_loads(" + (every_ > 0 ? "every " + std::to_string(every_) + " steps" : std::string("last")) + ")";
}

void WallLoadOutput::prepare(sim::Scene& s) {
  s.wall_loads.assign(s.walls.count(), {});  // from now on the wall stage sums them
  sums_.assign(s.walls.count(), {});
  s.walls.for_each([&](const auto& w, std::size_t k) {
    sums_[k].name = w.name;
    sums_[k].kind = std::decay_t<decltype(w)>::kind;
  });
}

void WallLoadOutput::start(sim::Scene& s) {
  prepare(s);
  if (sim::Comm::world().root()) {
    out_.open(file_, std::ios::trunc);
    if (!out_) throw std::runtime_error("cannot write '" + file_.string() + "'");
    out_ << kHeader << "\n";
  }
}

void WallLoadOutput::restart(sim::Scene& s, const sim::RestartPoint&) {
  prepare(s);
  // The rows up to the restored step are kept; summary.json's mean starts again from it.
  if (sim::Comm::world().root()) reopen_before(out_, file_, kHeader, s.clock.step + 1);
  last_step_ = s.clock.step;  // the restored step's loads are not known until it steps again
}

void WallLoadOutput::write_rows(const sim::Scene& s) {
  if (s.clock.step == last_step_ || s.wall_loads.empty()) return;
  last_step_ = s.clock.step;
  std::vector<double> v;
  for (const auto& l : s.wall_loads)
    for (int k = 0; k < 3; ++k) v.push_back(l.force[k]);
  for (const auto& l : s.wall_loads)
    for (int k = 0; k < 3; ++k) v.push_back(l.torque[k]);
  if (s.exchange) s.exchange->comm().sum_in_place(v);  // each rank summed its own particles
  const std::size_t n = s.wall_loads.size();
  std::string err;
  try {
    s.walls.for_each([&](const auto& w, std::size_t k) {
      auto& m = sums_[k];
      double axial = 0;
      if constexpr (requires { w.axis; w.angular_velocity; }) {
        m.has_axis = w.angular_velocity != 0;
        const sim::Vec3 a = w.R * w.axis;
        axial = a.x() * v[3 * n + 3 * k] + a.y() * v[3 * n + 3 * k + 1] + a.z() * v[3 * n + 3 * k + 2];
      }
      for (int c = 0; c < 3; ++c) m.last_force[c] = v[3 * k + c], m.last_torque[c] = v[3 * n + 3 * k + c];
      m.last_axial = axial;
      if (s.clock.time >= cfg_.average_after) {
        for (int c = 0; c < 3; ++c) m.force[c] += m.last_force[c], m.torque[c] += m.last_torque[c];
        m.axial += axial;
        ++m.rows;
      }
      if (out_.is_open()) {
        char buf[768];
        const sim::Vec3& x = w.position();
        int len = std::snprintf(buf, sizeof buf, "%lld,%.10g,%zu,%s,%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g",
                                static_cast<long long>(s.clock.step), s.clock.time, k, m.name.c_str(), m.kind.c_str(),
                                m.last_force[0], m.last_force[1], m.last_force[2], m.last_torque[0], m.last_torque[1],
                                m.last_torque[2], axial, x.x(), x.y(), x.z());
        // A controlled wall: its speed along its direction, the area and the normal stress (when it has an area).
        const sim::WallControl& c = w.control;
        const int room = static_cast<int>(sizeof buf) - len;
        if (c.active() && c.area_now > 0)
          len += std::snprintf(buf + len, room, ",%.10g,%.10g,%.10g\n", c.speed, c.area_now, c.load / c.area_now);
        else if (c.active())
          len += std::snprintf(buf + len, room, ",%.10g,,\n", c.speed);
        else
          len += std::snprintf(buf + len, room, ",,,\n");
        out_ << buf;
      }
    });
    if (out_.is_open()) {
      out_.flush();
      if (!out_) throw std::runtime_error("could not write '" + file_.string() + "' (disk full?)");
    }
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (sim::Comm::world().agree_error(err)) throw std::runtime_error(err);
}

void WallLoadOutput::run(sim::Scene& s) {
  if (reads_state(s)) write_rows(s);  // its cadence
}

void WallLoadOutput::finish(sim::Scene& s) {
  write_rows(s);
  if (out_.is_open()) out_.flush();
}

std::string WallLoadOutput::summary_json() const {
  std::ostringstream o;
  o.precision(10);
  auto vec = [&](const double* x, double scale) {
    std::ostringstream v;
    v.precision(10);
    v << "[" << x[0] * scale << ", " << x[1] * scale << ", " << x[2] * scale << "]";
    return v.str();
  };
  o << "\"wall_loads\": {\"file\": \"wall_loads.csv\", \"average_after_s\": " << cfg_.average_after << ", \"walls\": [";
  for (std::size_t k = 0; k < sums_.size(); ++k) {
    const auto& m = sums_[k];
    const double inv = m.rows > 0 ? 1.0 / static_cast<double>(m.rows) : 0.0;
    o << (k ? ", " : "") << "{\"wall\": " << k << ", \"name\": \"" << m.name << "\", \"kind\": \"" << m.kind
      << "\", \"rows_averaged\": " << m.rows << ", \"mean_force_N\": " << vec(m.force, inv)
      << ", \"mean_torque_Nm\": " << vec(m.torque, inv) << ", \"last_force_N\": " << vec(m.last_force, 1)
      << ", \"last_torque_Nm\": " << vec(m.last_torque, 1);
    if (m.has_axis) o << ", \"mean_axial_torque_Nm\": " << m.axial * inv << ", \"last_axial_torque_Nm\": " << m.last_axial;
    o << "}";
  }
  o << "]}";
  return o.str();
}

}  // namespace grains::io
