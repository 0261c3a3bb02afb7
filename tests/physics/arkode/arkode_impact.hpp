#pragma once
// Two-body normal impacts (sphere-sphere or sphere-wall) run through a case
// file with either integrator, measured against the analytic Hertz solution:
// contact time and maximum overlap from the sampled overlap and its rate
// (cubic Hermite between clock steps, so the sampling does not limit the
// accuracy), restitution from the velocities after the impact.
#include <cmath>
#include <chrono>
#include <sstream>
#include <string>

#include "sim/integrate/arkode.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test {

struct ImpactSpec {
  bool wall = false;
  double E = 1e7, nu = 0.3, rho = 2500, R = 0.001, v = 0.5, e = 1.0;
  std::string time_keys;   // e.g. "dt: 1e-7" plus integrator keys
};

struct ImpactRun {
  double restitution = 0, contact_time = 0, max_overlap = 0;
  double energy_drift = 0;  // (KE_after - e^2 KE_before) / KE_before
  double wall_seconds = 0;
  std::string stats;  // the ARKODE driver's figures, if any
  double rayleigh_time = 0;
  std::int64_t clock_steps = 0;
  // Analytic values.
  double tc_hertz = 0, dmax_hertz = 0;
};

/// Hertz (elastic) maximum overlap and contact time for effective E*, R*, m* and approach speed v.
inline void hertz(double Estar, double Rstar, double mstar, double v, double& dmax, double& tc) {
  dmax = std::pow(15 * mstar * v * v / (16 * Estar * std::sqrt(Rstar)), 0.4);
  // t_c = 2 dmax/v int_0^1 dx / sqrt(1 - x^{5/2}) = (4/5) B(2/5, 1/2) dmax / v.
  const double beta = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  tc = 0.8 * beta * dmax / v;
}

/// The cubic Hermite interpolant of (d0, r0) at 0 and (d1, r1) at h, and its maximum on [0, h].
struct Hermite {
  double d0, r0, d1, r1, h;
  double at(double s) const {  // s in [0, 1]
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * d0 + (s3 - 2 * s2 + s) * h * r0 + (-2 * s3 + 3 * s2) * d1 + (s3 - s2) * h * r1;
  }
  double slope(double s) const {
    const double s2 = s * s;
    return ((6 * s2 - 6 * s) * d0 + (3 * s2 - 4 * s + 1) * h * r0 + (-6 * s2 + 6 * s) * d1 + (3 * s2 - 2 * s) * h * r1) / h;
  }
  double maximum() const {
    double best = std::max(d0, d1);
    // Zeros of the slope (a quadratic in s).
    double a = 0, b = 1;
    if (r0 > 0 && r1 < 0) {
      for (int k = 0; k < 80; ++k) {
        const double m = 0.5 * (a + b);
        (slope(m) > 0 ? a : b) = m;
      }
      best = std::max(best, at(0.5 * (a + b)));
    }
    return best;
  }
};

inline ImpactRun run_impact(const ImpactSpec& c) {
  const double m = c.rho * 4.0 / 3.0 * M_PI * c.R * c.R * c.R;
  const double Estar = c.E / (2 * (1 - c.nu * c.nu));  // same material for both bodies (and the wall)
  const double Rstar = c.wall ? c.R : c.R / 2;
  const double mstar = c.wall ? m : m / 2;
  const double vrel = c.wall ? c.v : 2 * c.v;
  ImpactRun out;
  hertz(Estar, Rstar, mstar, vrel, out.dmax_hertz, out.tc_hertz);
  const double gap = 0.002 * c.R;
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [" << -4 * c.R << ", " << -2 * c.R << ", " << -2 * c.R << "], max: [" << 4 * c.R << ", "
    << 2 * c.R << ", " << 2 * c.R << "]}\n";
  y << "materials:\n" << material("m", c.rho, c.E, c.nu, c.e, 0);
  y << "particles:\n";
  if (c.wall) {
    y << single("a", "m", sim::Vec3(c.R + gap, 0, 0), c.R, sim::Vec3(-c.v, 0, 0));
    y << "walls:\n  - {type: plane, point: [0, 0, 0], normal: [1, 0, 0], material: m}\n";
  } else {
    y << single("a", "m", sim::Vec3(-c.R - gap, 0, 0), c.R, sim::Vec3(c.v, 0, 0));
    y << single("b", "m", sim::Vec3(c.R + gap, 0, 0), c.R, sim::Vec3(-c.v, 0, 0));
  }
  const double end = 1.5 * out.tc_hertz + 2 * gap / vrel;
  y << "time: {" << c.time_keys << ", end: " << end << "}\n";
  auto s = from_yaml(y.str());
  auto& sc = s.scene;
  out.rayleigh_time = s.rayleigh_time;
  out.clock_steps = sc.clock.n_steps;
  const auto t0 = std::chrono::steady_clock::now();
  s.pipeline.initialize(sc);
  auto gap_rate = [&](double& d, double& r) {
    const auto& p = sc.particles;
    if (c.wall) {
      d = c.R - p.x[0][0];
      r = -p.v[0][0];
    } else {
      const std::size_t a = index_of(p, 0), b = index_of(p, 1);
      d = 2 * c.R - (p.x[b] - p.x[a]).norm();
      r = p.v[a][0] - p.v[b][0];
    }
  };
  double d0, r0;
  gap_rate(d0, r0);
  const double t_touch = -d0 / r0;  // free flight to the first touch
  // The overlap between samples: a cubic Hermite through (d, d') at both
  // ends. Samples are the clock steps, or each accepted ARKODE step.
  double t_prev = sc.clock.time, dmax = 0;
  auto sample = [&](double t) {
    double d1, r1;
    gap_rate(d1, r1);
    if (t > t_prev && (d0 > 0 || d1 > 0)) dmax = std::max(dmax, Hermite{d0, r0, d1, r1, t - t_prev}.maximum());
    d0 = d1;
    r0 = r1;
    t_prev = t;
  };
  bool per_step = false;
  for (const auto& st : s.pipeline.stages())
    if (auto* a = dynamic_cast<sim::ArkodeIntegrator*>(st.get())) {
      a->set_step_observer([&](const sim::Scene& x) { sample(x.clock.time); });
      per_step = true;
    }
  while (sc.clock.step < sc.clock.n_steps) {
    s.pipeline.step(sc);
    if (!per_step) sample(sc.clock.time);
  }
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const auto& st : s.pipeline.stages()) out.stats += st->summary_json();
  const auto& p = sc.particles;
  const double vout = c.wall ? p.v[0][0] : p.v[index_of(p, 1)][0] - p.v[index_of(p, 0)][0];
  out.restitution = vout / vrel;
  // Free flight is integrated exactly by both integrators (zero force), so
  // the contact begins at gap/vrel and ends where the final gap, run back at
  // the final speed, closes: no sampling in the contact time.
  double d_end, r_end;
  gap_rate(d_end, r_end);
  out.contact_time = (sc.clock.time + d_end / (-r_end)) - t_touch;
  out.max_overlap = dmax;
  out.energy_drift = out.restitution * out.restitution - c.e * c.e;
  return out;
}

}  // namespace grains::test
