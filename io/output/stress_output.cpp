#include "io/output/stress_output.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "io/output/csv_rows.hpp"
#include "sim/parallel/comm.hpp"
#include "sim/parallel/exchange.hpp"

namespace grains::io {

namespace fs = std::filesystem;

namespace {

const char* kSym[6] = {"xx", "yy", "zz", "xy", "xz", "yz"};

std::string sym_columns(const char* prefix) {
  std::string h;
  for (const char* c : kSym) h += std::string(",") + prefix + c + "_Pa";
  return h;
}

std::string stress_header() {
  return "step,time_s,volume_m3,grains,solid_fraction,vx_mps,vy_mps,vz_mps" + sym_columns("s") + sym_columns("k") +
         ",pressure_Pa";
}
std::string profile_header() {
  return "step,time_s,bin,position_m,grains,solid_fraction,vx_mps,vy_mps,vz_mps" + sym_columns("s") +
         sym_columns("k");
}

// The volume of a sphere (centre c, radius r along the axis) between a and b.
double slab_volume(double c, double r, double a, double b) {
  const double z0 = std::max(a, c - r) - c, z1 = std::min(b, c + r) - c;
  if (!(z1 > z0)) return 0;
  return M_PI * (r * r * (z1 - z0) - (z1 * z1 * z1 - z0 * z0 * z0) / 3);
}

// Mean of each column after the first `skip` over the rows whose time
// (column 1) is at or after t0, grouped by the key column (-1: one group).
struct Means {
  std::vector<std::vector<double>> sum;
  std::vector<std::int64_t> rows;
};
Means column_means(const fs::path& file, double t0, int key) {
  Means m;
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
    if (v.size() < 3 || v[1] < t0) continue;
    const std::size_t g = key < 0 ? 0 : static_cast<std::size_t>(v[static_cast<std::size_t>(key)]);
    if (m.sum.size() <= g) m.sum.resize(g + 1), m.rows.resize(g + 1, 0);
    if (m.sum[g].empty()) m.sum[g].assign(v.size(), 0.0);
    for (std::size_t k = 0; k < v.size() && k < m.sum[g].size(); ++k) m.sum[g][k] += v[k];
    ++m.rows[g];
  }
  for (std::size_t g = 0; g < m.sum.size(); ++g)
    for (auto& x : m.sum[g]) x /= static_cast<double>(std::max<std::int64_t>(1, m.rows[g]));
  return m;
}

}  // namespace

void box_region(const sim::Scene& s, sim::Vec3& lo, sim::Vec3& hi) {
  for (int d = 0; d < 3; ++d) {
    lo[d] = s.domain.lo[d], hi[d] = s.domain.hi[d];
    if (s.domain.periodic[d]) continue;
    double a, b;
    if (s.walls.facing_planes(d, a, b) && b > a) lo[d] = a, hi[d] = b;
  }
}

StressOutput::StressOutput(fs::path dir, StressConfig cfg, std::int64_t every_steps)
    : dir_(std::move(dir)), cfg_(std::move(cfg)), every_(std::max<std::int64_t>(1, every_steps)) {}

std::string StressOutput::name() const {
  return "output.stress(every " + std::to_string(every_) + " steps" +
         (cfg_.bins > 0 ? ", " + std::to_string(cfg_.bins) + " bins" : std::string()) + ")";
}

void StressOutput::open(bool restarting, std::int64_t step) {
  if (!sim::Comm::world().root()) return;
  const fs::path sf = dir_ / "stress.csv", pf = dir_ / "profile.csv";
  if (restarting) {
    reopen_before(stress_, sf, stress_header(), step + 1);
    if (cfg_.bins > 0) reopen_before(profile_, pf, profile_header(), step + 1);
    return;
  }
  stress_.open(sf, std::ios::trunc);
  if (!stress_) throw std::runtime_error("cannot write '" + sf.string() + "'");
  stress_ << stress_header() << "\n";
  if (cfg_.bins > 0) {
    profile_.open(pf, std::ios::trunc);
    if (!profile_) throw std::runtime_error("cannot write '" + pf.string() + "'");
    profile_ << profile_header() << "\n";
  }
}

void StressOutput::start(sim::Scene& s) {
  open(false, 0);
  arm(s);
}

void StressOutput::restart(sim::Scene& s, const sim::RestartPoint&) {
  open(true, s.clock.step);
  arm(s);
}

void StressOutput::arm(sim::Scene& s) {
  // Off the chain of armed probes (another, the pressure servo's, may follow).
  if (s.stress_probe == &probe_) s.stress_probe = probe_.next;
  // Its cadence, and the last step (the run's final state).
  if ((s.clock.step + 1) % every_ != 0 && s.clock.step + 1 != s.clock.n_steps) return;
  if (cfg_.region_given)
    probe_.lo = cfg_.lo, probe_.hi = cfg_.hi;
  else
    box_region(s, probe_.lo, probe_.hi);
  for (int d = 0; d < 3; ++d) {
    probe_.period_lo[d] = s.domain.lo[d];
    probe_.period[d] = s.domain.periodic[d] ? s.domain.hi[d] - s.domain.lo[d] : 0.0;
  }
  probe_.shear_flow = s.domain.shear.flow;
  probe_.shear_gradient = s.domain.shear.gradient;
  if (s.domain.shear.on()) probe_.shear_offset = s.domain.shear_offset(s.clock.time + s.clock.dt);  // the measured step's
  probe_.axis = std::max(cfg_.axis, 0);
  probe_.bins = cfg_.bins;
  probe_.reset(omp_get_max_threads());
  probe_.next = s.stress_probe;
  s.stress_probe = &probe_;
}

void StressOutput::run(sim::Scene& s) {
  if (s.stress_probe == &probe_) measure(s);
  arm(s);
}

void StressOutput::measure(sim::Scene& s) {
  const sim::StressProbe& pr = probe_;
  const int B = 1 + pr.bins;  // the region, then the bins
  const auto ub = static_cast<std::size_t>(B);
  const sim::ParticleStore& p = s.particles;
  const std::size_t n = p.n_owned();
  const int ax = pr.axis;
  const double width = pr.bins > 0 ? (pr.hi[ax] - pr.lo[ax]) / pr.bins : 0.0;
  // Where each grain is: its bin (or -1 outside the region across the axis)
  // and whether its centre is in the region.
  std::vector<int> bin(n, -2);
  // Positions (and velocities, across a sheared face) brought into the domain.
  std::vector<sim::Vec3> x(n), vel(p.v.begin(), p.v.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t i = 0; i < n; ++i) {
    sim::Vec3 c = p.x[i];
    s.domain.wrap(c, vel[i], s.clock.time);
    x[i] = c;
    bool across = true;  // inside the region along the other axes
    for (int d = 0; d < 3; ++d)
      if (d != ax && !(c[d] >= pr.lo[d] && c[d] < pr.hi[d])) across = false;
    if (!across) continue;
    bin[i] = -1;
    if (c[ax] >= pr.lo[ax] && c[ax] < pr.hi[ax])
      bin[i] = pr.bins > 0 ? std::min(pr.bins - 1, static_cast<int>((c[ax] - pr.lo[ax]) / width)) : 0;
  }
  auto radius_of = [&](std::size_t i) {  // an ellipsoid: its equal-volume sphere
    if (p.fields().has(sim::Field::SemiAxes) && p.shape[i] == sim::kEllipsoid) {
      const sim::Vec3& a = p.semi_axes[i];
      return std::cbrt(a.x() * a.y() * a.z());
    }
    return p.radius[i];
  };
  // Pass 1: contact sums (B x 6), then per group mass, momentum (3), count, solid volume.
  std::vector<double> v(ub * 12, 0.0);
  for (const auto& rows : pr.rows)
    for (std::size_t g = 0; g < ub; ++g)
      for (std::size_t k = 0; k < 6; ++k) v[6 * g + k] += rows[g][k];
  double* grp = v.data() + 6 * ub;
  auto add_to = [&](std::size_t g, std::size_t i, double vol) {
    double* q = grp + 6 * g;
    q[0] += p.mass[i];
    for (int d = 0; d < 3; ++d) q[1 + d] += p.mass[i] * vel[i][d];
    q[4] += 1;
    q[5] += vol;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (bin[i] == -2) continue;
    const double r = radius_of(i);
    if (bin[i] >= 0) add_to(0, i, 4.0 / 3.0 * M_PI * r * r * r);
    if (pr.bins == 0) continue;
    // The bins its sphere reaches get its slab volumes (along a periodic
    // axis its images' too); the one of its centre its mass.
    const double L = pr.period[ax];
    for (const int k : {0, 1, -1}) {
      if (k != 0 && !(L > 0)) break;  // (a non-periodic axis: the sphere itself only)
      const double c = x[i][ax] + k * L;
      const int b0 = std::max(0, static_cast<int>(std::floor((c - r - pr.lo[ax]) / width)));
      const int b1 = std::min(pr.bins - 1, static_cast<int>(std::floor((c + r - pr.lo[ax]) / width)));
      for (int b = b0; b <= b1; ++b)
        grp[6 * (1 + b) + 5] += slab_volume(c, r, pr.lo[ax] + b * width, pr.lo[ax] + (b + 1) * width);
    }
    if (bin[i] >= 0) {
      add_to(static_cast<std::size_t>(1 + bin[i]), i, 0.0);
    }
  }
  if (s.exchange) s.exchange->comm().sum_in_place(v);
  std::vector<sim::Vec3> u(ub, sim::Vec3::Zero());
  for (std::size_t g = 0; g < ub; ++g)
    if (grp[6 * g] > 0) u[g] = sim::Vec3(grp[6 * g + 1], grp[6 * g + 2], grp[6 * g + 3]) / grp[6 * g];
  // Pass 2: the kinetic sums about the bin's mean velocity (the region's without bins).
  std::vector<double> kin(ub * 6, 0.0);
  auto add_kin = [&](std::size_t g, const sim::Vec3& w, double m) {
    double* q = kin.data() + 6 * g;
    q[0] += m * w.x() * w.x(), q[1] += m * w.y() * w.y(), q[2] += m * w.z() * w.z();
    q[3] += m * w.x() * w.y(), q[4] += m * w.x() * w.z(), q[5] += m * w.y() * w.z();
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (bin[i] < 0) continue;
    const std::size_t g = pr.bins > 0 ? static_cast<std::size_t>(1 + bin[i]) : 0;
    const sim::Vec3 w = vel[i] - u[g];
    if (pr.bins > 0) add_kin(g, w, p.mass[i]);
    add_kin(0, w, p.mass[i]);  // the region: the sum of its bins' fluctuations
  }
  if (s.exchange) s.exchange->comm().sum_in_place(kin);
  std::string err;
  if (stress_.is_open()) try {  // (every rank goes on to agree_error)
    const double V = (pr.hi - pr.lo).prod(), Vb = pr.bins > 0 ? V / pr.bins : 0.0;
    char buf[1024];
    auto row = [&](std::size_t g, double vol, int len) {
      const double* c = v.data() + 6 * g;
      const double* k = kin.data() + 6 * g;
      for (int j = 0; j < 3; ++j)
        len += std::snprintf(buf + len, sizeof buf - len, ",%.10g", u[g][j]);
      for (int j = 0; j < 6; ++j) len += std::snprintf(buf + len, sizeof buf - len, ",%.10g", (c[j] + k[j]) / vol);
      for (int j = 0; j < 6; ++j) len += std::snprintf(buf + len, sizeof buf - len, ",%.10g", k[j] / vol);
      return len;
    };
    int len = std::snprintf(buf, sizeof buf, "%lld,%.10g,%.10g,%lld,%.10g", static_cast<long long>(s.clock.step),
                            s.clock.time, V, static_cast<long long>(grp[4]), grp[5] / V);
    len = row(0, V, len);
    const double* c = v.data();
    const double* k = kin.data();
    std::snprintf(buf + len, sizeof buf - len, ",%.10g\n", (c[0] + c[1] + c[2] + k[0] + k[1] + k[2]) / (3 * V));
    stress_ << buf;
    for (int b = 0; b < pr.bins; ++b) {
      const auto g = static_cast<std::size_t>(1 + b);
      len = std::snprintf(buf, sizeof buf, "%lld,%.10g,%d,%.10g,%lld,%.10g", static_cast<long long>(s.clock.step),
                          s.clock.time, b, pr.lo[ax] + (b + 0.5) * width, static_cast<long long>(grp[6 * g + 4]),
                          grp[6 * g + 5] / Vb);
      len = row(g, Vb, len);
      std::snprintf(buf + len, sizeof buf - len, "\n");
      profile_ << buf;
    }
    stress_.flush();
    if (profile_.is_open()) profile_.flush();
    if (!stress_ || (profile_.is_open() && !profile_))
      throw std::runtime_error("could not write '" + (dir_ / "stress.csv").string() + "' (disk full?)");
  } catch (const std::exception& e) {
    err = e.what();
  }
  if (sim::Comm::world().agree_error(err)) throw std::runtime_error(err);
}

void StressOutput::finish(sim::Scene& s) {
  if (s.stress_probe == &probe_) s.stress_probe = probe_.next;
  if (!sim::Comm::world().root() || !stress_.is_open()) return;
  stress_.close();
  if (profile_.is_open()) profile_.close();
  // The means over the rows from average_after on, from the files (all the
  // run's rows, restarts included).
  const Means m = column_means(dir_ / "stress.csv", cfg_.average_after, -1);
  std::ostringstream o;
  o.precision(10);
  const std::int64_t rows = m.rows.empty() ? 0 : m.rows[0];
  o << "\"stress\": {\"file\": \"stress.csv\", \"average_after_s\": " << cfg_.average_after
    << ", \"rows_averaged\": " << rows;
  if (rows > 0) {
    const auto& a = m.sum[0];
    auto list = [&](std::size_t from, std::size_t count) {
      std::ostringstream l;
      l.precision(10);
      l << "[";
      for (std::size_t j = 0; j < count; ++j) l << (j ? ", " : "") << a[from + j];
      return l.str() + "]";
    };
    o << ", \"mean_solid_fraction\": " << a[4] << ", \"mean_velocity_mps\": " << list(5, 3)
      << ", \"mean_stress_Pa\": " << list(8, 6) << ", \"mean_kinetic_stress_Pa\": " << list(14, 6)
      << ", \"mean_pressure_Pa\": " << a[20];
  }
  if (cfg_.bins > 0) {
    o << ", \"profile\": \"profile.csv\", \"profile_mean\": \"profile_mean.csv\"";
    const Means pm = column_means(dir_ / "profile.csv", cfg_.average_after, 2);
    std::ofstream out(dir_ / "profile_mean.csv", std::ios::trunc);
    std::string h = profile_header();
    h = "rows" + h.substr(h.find(",bin") + 0);  // rows, bin, position_m, ...
    out << h << "\n";
    out.precision(10);
    for (std::size_t b = 0; b < pm.sum.size(); ++b) {
      if (pm.rows[b] == 0) continue;
      out << pm.rows[b];
      for (std::size_t j = 2; j < pm.sum[b].size(); ++j) out << "," << pm.sum[b][j];
      out << "\n";
    }
    if (!out) throw std::runtime_error("could not write '" + (dir_ / "profile_mean.csv").string() + "'");
  }
  o << "}";
  summary_ = o.str();
}

std::string StressOutput::summary_json() const { return summary_; }

}  // namespace grains::io
