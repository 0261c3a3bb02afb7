#pragma once
// One head-on impact run as a case (tests/physics/contact): sphere-sphere or
// sphere-plane, with the crossing times of zero overlap interpolated.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "tests/support/sim_helpers.hpp"

namespace grains::test {

struct ImpactResult {
  double restitution;
  double contact_time;
  double max_overlap;
};

/// The Hertz contact time of a head-on impact (sphere-sphere at +-v, or on a wall at v).
inline double hertz_contact_time(bool wall, double E, double nu, double rho, double R, double v) {
  const double m = rho * 4.0 / 3.0 * M_PI * R * R * R;
  const double Estar = wall ? 1.0 / (2 * (1 - nu * nu) / E) : E / (2 * (1 - nu * nu));
  const double Rstar = wall ? R : R / 2;
  const double mstar = wall ? m : m / 2;
  const double vrel = wall ? v : 2 * v;
  return 2.8683 * std::pow(mstar * mstar / (Rstar * Estar * Estar * vrel), 0.2);
}

/// Runs one head-on collision of equal spheres at +-v (or one sphere on a
/// plane at v) with time step dt = tc / steps_per_contact and measures it.
/// `contact` is an optional contact: section (e.g. another normal law);
/// tc defaults to the Hertz contact time.
inline ImpactResult impact(bool wall, double E, double nu, double rho, double R, double v, double e,
                           int steps_per_contact, const std::string& contact = "", double tc = 0) {
  if (tc <= 0) tc = hertz_contact_time(wall, E, nu, rho, R, v);
  const double vrel = wall ? v : 2 * v;
  const double dt = tc / steps_per_contact;
  std::ostringstream y;
  y.precision(17);
  const double gap = 0.02 * R;  // start just apart
  y << "domain: {min: [" << -4 * R << ", " << -2 * R << ", " << -2 * R << "], max: [" << 4 * R << ", " << 2 * R << ", "
    << 2 * R << "]}\n";
  y << "materials:\n" << material("m", rho, E, nu, e, 0);
  if (!contact.empty()) y << "contact: " << contact << "\n";
  y << "particles:\n";
  if (wall) {
    y << single("a", "m", sim::Vec3(R + gap, 0, 0), R, sim::Vec3(-v, 0, 0));
    y << "walls:\n  - {type: plane, point: [0, 0, 0], normal: [1, 0, 0], material: m}\n";
  } else {
    y << single("a", "m", sim::Vec3(-R - gap, 0, 0), R, sim::Vec3(v, 0, 0));
    y << single("b", "m", sim::Vec3(R + gap, 0, 0), R, sim::Vec3(-v, 0, 0));
  }
  y << "time: {dt: " << dt << ", end: " << 3 * tc + 4 * gap / vrel << "}\n";
  auto s = from_yaml(y.str());
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  auto overlap = [&] {
    const auto& p = sc.particles;
    if (wall) return R - p.x[0][0];
    return 2 * R - (p.x[index_of(p, 1)] - p.x[index_of(p, 0)]).norm();
  };
  double prev = overlap(), t_in = -1, t_out = -1, dmax = 0;
  while (sc.clock.step < sc.clock.n_steps) {
    s.pipeline.step(sc);
    const double d = overlap();
    dmax = std::max(dmax, d);
    if (prev <= 0 && d > 0 && t_in < 0) t_in = sc.clock.time - dt * d / (d - prev);
    if (prev > 0 && d <= 0 && t_in >= 0 && t_out < 0) t_out = sc.clock.time - dt * d / (d - prev);
    prev = d;
  }
  const auto& p = sc.particles;
  const double vout = wall ? p.v[0][0] : p.v[index_of(p, 1)][0] - p.v[index_of(p, 0)][0];
  return {vout / vrel, t_out - t_in, dmax};
}

/// The case of one sphere (radius R, centre (x0, y0, 0), at rest) of a
/// material with surface energy g and restitution 0.5 next to `wall` (whose
/// surface there is the plane x = 0, facing +x), pulled along +x by a body
/// acceleration `pull`; `contact`: the contact section; `neighbor`: an
/// optional neighbor section. For the pull-off tests of adhesive laws.
inline std::string pulled_case(double E, double nu, double rho, double R, double g, double pull,
                               const std::string& contact, const std::string& wall, double x0, double y0,
                               const std::string& neighbor, double end) {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [" << -2 * R << ", " << -2 * R << ", " << -2 * R << "], max: [" << 40 * R << ", " << 2 * R
    << ", " << 2 * R << "]}\n";
  y << "gravity: [" << pull << ", 0, 0]\n";
  y << "materials:\n  - {name: m, density: " << rho << ", youngs_modulus: " << E << ", poisson_ratio: " << nu
    << ", restitution: 0.5, surface_energy: " << g << "}\n";
  y << "contact: " << contact << "\n";
  y << "particles:\n" << single("a", "m", sim::Vec3(x0, y0, 0), R, sim::Vec3::Zero());
  y << "walls:\n  - " << wall << "\n";
  if (!neighbor.empty()) y << "neighbor: " << neighbor << "\n";
  y << "time: {dt_rayleigh: 0.1, end: " << end << "}\n";
  return y.str();
}

/// An adhesive normal law without adhesion (the materials have no surface
/// energy) is the Hertz law bit for bit: the impacts of two spheres and of a
/// sphere on a wall, at 0.3 m/s with e = 0.6, give identical restitution,
/// contact time and largest overlap. `contact`: the law's contact section.
inline void expect_hertz_impacts(const std::string& contact, double E, double nu, double rho, double R) {
  for (const bool wall : {false, true}) {
    SCOPED_TRACE((wall ? "sphere-wall, " : "sphere-sphere, ") + contact);
    const auto h = impact(wall, E, nu, rho, R, 0.3, 0.6, 200, "{model: hertz, tangential: none}");
    const auto a = impact(wall, E, nu, rho, R, 0.3, 0.6, 200, contact);
    EXPECT_EQ(a.restitution, h.restitution);
    EXPECT_EQ(a.contact_time, h.contact_time);
    EXPECT_EQ(a.max_overlap, h.max_overlap);
    EXPECT_NEAR(h.restitution, 0.6, 0.01);
  }
}

}  // namespace grains::test
