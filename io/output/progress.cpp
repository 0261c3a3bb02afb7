#include "io/output/progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "sim/parallel/comm.hpp"

namespace grains::io {

Progress::Progress(std::ostream& out, double interval) : out_(out), interval_(interval) {}

void Progress::run(sim::Scene& s) {
  const auto now = std::chrono::steady_clock::now();
  if (start_step_ < 0) {
    start_ = last_ = now;
    start_step_ = s.clock.step - 1;
  }
  particle_steps_ += static_cast<double>(s.particles.n_owned());
  const auto& comm = sim::Comm::world();
  bool due = std::chrono::duration<double>(now - last_).count() >= interval_;
  if (comm.parallel()) {
    // Ranks decide together (every 32 steps), so the counts can be summed.
    if (s.clock.step % 32 != 0) return;
    due = comm.any(due);
  }
  if (due) {
    last_ = now;
    print(s, false);
  }
}

void Progress::finish(sim::Scene& s) {
  if (start_step_ >= 0) print(s, true);
}

void Progress::print(const sim::Scene& s, bool final) {
  const auto& comm = sim::Comm::world();
  const auto particles = static_cast<std::size_t>(comm.sum(static_cast<std::int64_t>(s.particles.n_owned())));
  const double psteps = comm.sum(particle_steps_);
  if (!comm.root()) return;
  const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const auto done = s.clock.step - start_step_;
  const auto left = s.clock.n_steps - s.clock.step;
  const double eta = done > 0 ? el / static_cast<double>(done) * static_cast<double>(left) : 0;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%sstep %lld/%lld (%5.1f%%)  t = %.6g s  %s %.0f s  %zu particles  %.3g particle-steps/s",
                final ? "done: " : "", static_cast<long long>(s.clock.step), static_cast<long long>(s.clock.n_steps),
                s.clock.n_steps > 0 ? 100.0 * static_cast<double>(s.clock.step) / static_cast<double>(s.clock.n_steps) : 100.0,
                s.clock.time, final ? "wall" : "ETA", final ? el : eta, particles,
                el > 0 ? psteps / el : 0.0);
  out_ << buf << std::endl;
}

BlowUpCheck::BlowUpCheck(const sim::Scene& s, double rayleigh_time, std::int64_t every, double extra_speed)
    : rayleigh_(rayleigh_time), every_(every) {
  const sim::Vec3 ext = s.domain.hi - s.domain.lo;
  double v0 = 0;
  for (std::size_t i = 0; i < s.particles.n_owned(); ++i) v0 = std::max(v0, s.particles.v[i].norm());
  v0 = sim::Comm::world().max(v0);
  const double vfall = std::sqrt(2 * s.gravity.norm() * ext.norm());
  vmax_ = 100 * (v0 + vfall + s.walls.max_speed() + extra_speed) + 1e-6;
}

void BlowUpCheck::run(sim::Scene& s) {
  if (s.clock.step % every_ != 0) return;
  std::string d = diagnose(s);
  if (!sim::Comm::world().agree_error(d)) return;  // every rank stops together
  if (!last_good_.empty())
    d += ". The last good checkpoint is " + last_good_ + " (written before the blow-up and kept)";
  throw BlowUp(d);
}

std::string BlowUpCheck::diagnose(const sim::Scene& s) const {
  const auto& p = s.particles;
  std::ostringstream o;
  o.precision(4);
  o << "blow-up at step " << s.clock.step << " (t = " << s.clock.time << " s): ";
  bool bad = false;
  for (std::size_t i = 0; i < p.n_owned() && !bad; ++i) {
    const bool finite = p.x[i].allFinite() && p.v[i].allFinite();
    const double speed = finite ? p.v[i].norm() : 0;
    if (finite && speed <= vmax_) continue;
    bad = true;
    o << "particle id " << p.id[i] << " (radius " << p.radius[i] << " m) has ";
    if (!finite)
      o << "a non-finite position or velocity";
    else
      o << "speed " << speed << " m/s, above the plausible bound " << vmax_ << " m/s";
  }
  // Overlaps far beyond any elastic contact (list entries are pairs within the skin).
  const auto& nl = s.neighbors;
  const std::size_t rows = std::min(p.n_owned(), nl.row_start.empty() ? std::size_t{0} : nl.row_start.size() - 1);
  for (std::size_t i = 0; i < rows && !bad; ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const auto j = nl.partner[k];
      // For non-spherical bodies the radius bounds the shape: bounding
      // spheres may overlap a lot without the bodies touching.
      if (p.shape[i] != sim::kSphere || p.shape[j] != sim::kSphere) continue;
      const double rmin = std::min(p.radius[i], p.radius[j]);
      const double overlap = p.radius[i] + p.radius[j] - (p.x[i] - p.x[j]).norm();
      if (!(overlap > 0.5 * rmin)) continue;
      bad = true;
      o << "particles id " << p.id[i] << " and id " << p.id[j] << " overlap by " << overlap << " m, "
        << 100 * overlap / rmin << "% of the smaller radius";
      break;
    }
  if (!bad) return {};
  o << ". Likely cause: ";
  const double frac = s.clock.dt / rayleigh_;
  if (frac > 0.3)
    o << "the time step dt = " << s.clock.dt << " s is " << frac
      << " Rayleigh times; use time.dt_rayleigh: 0.2";
  else if (s.clock.step <= every_)
    o << "overlapping initial positions or a wall placed through particles (the state went bad within "
      << s.clock.step << " steps of the start)";
  else
    o << "extreme or unsupported material values (check youngs_modulus, density and restitution) or "
         "particles driven into each other by a moving wall";
  return o.str();
}

}  // namespace grains::io
