#pragma once
// The protocols of the packing regression suite (tests/regression, CI and
// long sizes) and what they share: the reference table, the result records
// that docs/packing.md is generated from, and small statistics.
//
// * references: tests/regression/packing_references.yaml holds every
//   reference value, the band a test accepts, why, and the source. Tests look
//   their entries up by key (reference()), print them and assert against
//   them; tests/regression/make_packing_doc.py prints the same table.
// * records: with GRAINS_RESULTS_DIR set, record() writes one JSON file per
//   measurement there (tests/regression/make_packing_doc.sh sets it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "io/output/mass_output.hpp"
#include "postprocess/contacts.hpp"
#include "postprocess/frame.hpp"
#include "postprocess/packing_fraction.hpp"
#include "sim/integrate/radius_growth.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test::packing {

// ---------------------------------------------------------------- references

struct Reference {
  std::string key, quantity, source, band_reason;
  double value = 0;  // NaN where the reference is a range or a statement (`text`)
  std::string text;  // the reference as written in the table
  double lo = -INFINITY, hi = INFINITY;  // the band a test accepts
};

inline Reference reference(const std::string& key) {
  static const YAML::Node table =
      YAML::LoadFile(std::string(GRAINS_SOURCE_DIR) + "/tests/regression/packing_references.yaml");
  const YAML::Node n = table[key];
  if (!n) throw std::runtime_error("no entry '" + key + "' in tests/regression/packing_references.yaml");
  Reference r;
  r.key = key;
  r.quantity = n["quantity"].as<std::string>();
  r.source = n["source"].as<std::string>();
  r.text = n["reference"].as<std::string>();
  try {
    r.value = n["reference"].as<double>();
  } catch (const YAML::BadConversion&) {
    r.value = NAN;
  }
  if (n["band"]) {
    r.lo = n["band"][0].as<double>();
    r.hi = n["band"][1].as<double>();
  }
  if (n["band_reason"]) r.band_reason = n["band_reason"].as<std::string>();
  std::cout << "reference " << key << ": " << r.quantity << " = " << r.text << ", accepted [" << r.lo << ", " << r.hi
            << "] (" << r.band_reason << "); source: " << r.source << "\n";
  return r;
}

/// Asserts value in the reference's band, with the reference in the message.
inline void expect_in_band(const Reference& r, double value, const std::string& what = "") {
  EXPECT_GE(value, r.lo) << r.key << (what.empty() ? "" : " (" + what + ")") << ": " << value << " below the band ["
                         << r.lo << ", " << r.hi << "]; reference " << r.text << " (" << r.source << ")";
  EXPECT_LE(value, r.hi) << r.key << (what.empty() ? "" : " (" + what + ")") << ": " << value << " above the band ["
                         << r.lo << ", " << r.hi << "]; reference " << r.text << " (" << r.source << ")";
}

// ------------------------------------------------------------------- records

/// A flat JSON object built field by field.
class Record {
 public:
  Record& num(const std::string& k, double v) {
    std::ostringstream o;
    o.precision(10);
    o << v;
    return raw(k, std::isfinite(v) ? o.str() : "null");
  }
  Record& str(const std::string& k, const std::string& v) { return raw(k, "\"" + v + "\""); }
  Record& nums(const std::string& k, const std::vector<double>& v) {
    std::ostringstream o;
    o.precision(10);
    o << "[";
    for (std::size_t i = 0; i < v.size(); ++i) o << (i ? ", " : "") << v[i];
    o << "]";
    return raw(k, o.str());
  }
  std::string text() const { return "{\n" + body_ + "\n}\n"; }

 private:
  Record& raw(const std::string& k, const std::string& v) {
    body_ += (body_.empty() ? "  \"" : ",\n  \"") + k + "\": " + v;
    return *this;
  }
  std::string body_;
};

/// Writes $GRAINS_RESULTS_DIR/<name>.json (nothing without the variable).
inline void record(const std::string& name, const Record& r) {
  const char* dir = std::getenv("GRAINS_RESULTS_DIR");
  if (!dir || !*dir) return;
  std::filesystem::create_directories(dir);
  std::ofstream o(std::filesystem::path(dir) / (name + ".json"));
  o << r.text();
}

// ---------------------------------------------------------------- statistics

inline double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}
/// Sample standard deviation (n - 1).
inline double stddev(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0;
  for (double x : v) s += (x - m) * (x - m);
  return v.size() > 1 ? std::sqrt(s / static_cast<double>(v.size() - 1)) : 0.0;
}

/// y = a + b x by least squares, with standard errors from the residuals.
struct LineFit {
  double a = 0, b = 0, se_a = 0, se_b = 0, r2 = 0;
};
inline LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  const double mx = mean(x), my = mean(y);
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  LineFit f;
  f.b = sxy / sxx;
  f.a = my - f.b * mx;
  double rss = 0;
  for (std::size_t i = 0; i < x.size(); ++i) rss += std::pow(y[i] - f.a - f.b * x[i], 2);
  const double s2 = x.size() > 2 ? rss / (n - 2) : 0.0;
  f.se_b = std::sqrt(s2 / sxx);
  f.se_a = std::sqrt(s2 * (1 / n + mx * mx / sxx));
  f.r2 = syy > 0 ? 1 - rss / syy : 1;
  return f;
}

/// A number as a case-file override value (12 significant digits).
inline std::string num(double v) {
  std::ostringstream o;
  o.precision(12);
  o << v;
  return o.str();
}

inline void run_steps(io::Simulation& s, std::int64_t until_step) {
  while (s.scene.clock.step < until_step) s.pipeline.step(s.scene);
}

/// The owned spheres of the scene now as a postprocess frame (centres, radii, time).
inline postprocess::Frame sphere_frame(const sim::Scene& sc) {
  postprocess::Frame f;
  const auto& p = sc.particles;
  f.x.assign(p.x.begin(), p.x.begin() + static_cast<std::ptrdiff_t>(p.n_owned()));
  f.radius.assign(p.radius.begin(), p.radius.begin() + static_cast<std::ptrdiff_t>(p.n_owned()));
  f.time = sc.clock.time;
  return f;
}

inline double mean_speed(const sim::Scene& sc) {
  const auto& p = sc.particles;
  double ke = 0, m = 0;
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    ke += 0.5 * p.mass[i] * p.v[i].squaredNorm();
    m += p.mass[i];
  }
  return m > 0 ? std::sqrt(2 * ke / m) : 0.0;
}

// -------------------------------------------------------------------- pours

// Seed-to-seed standard deviation of the bulk packing fraction of one CI
// pour (3,000 spheres, 10 d x 10 d), measured over seeds 1-4 at every
// friction of the sweep (2026-11-21; re-measured and checked by
// PackingLong.FrictionSweepSeedSpread): pooled 0.0016, largest 0.0027
// (mu = 0.5); 0.002 is used. A difference of two runs then has a standard
// deviation of sqrt(2) x 0.002 = 0.0028, and the mean steps of the sweep,
// 0.021, 0.024, 0.0095 and 0.011, are at least 3.4 of those: requiring every
// step to fall fails a correct code with probability < 0.1 % in all, while
// a flat step (no friction dependence) passes with probability 1/2 and the
// whole flat sweep with 1/16, and fails the drop check.
constexpr double kPourSigma = 0.002;
const std::vector<double> kFrictions = {0, 0.1, 0.3, 0.5, 1};

/// Frictional (or frictionless) spheres poured into a box (cases/pour_spheres:
/// d = 1 mm, rho = 2500, E = 10 MPa, nu = 0.3, e = 0.5, walls of the same
/// material) at friction mu; bulk packing fraction 2 d from the walls, the
/// floor and the free surface (exact sphere-box volumes).
struct PourConfig {
  int count = 3000;
  double width = 0.01;      // box side (m)
  double fill_top = 0.062;  // top of the random fill region (m): fill fraction ~0.26
  double end = 0.3;         // s: fall (0.11 s from the top) and settle
  double end_frictionless = 0.4;  // s: without friction only the normal damping stops
                                  // the grains (rms speed 2e-3 m/s at 0.25 s, 8e-4 at 0.3-0.5 s)
  int seed = 1;
};
struct PourResult {
  double phi = 0, speed = 0, bulk_height = 0;  // speed: rms over the bulk region
  std::size_t n = 0;
};
/// Settled pour: the rms speed of the bulk grains below this. Frictional beds
/// come to rest (1e-6 m/s); a frictionless bed keeps a residual agitation of
/// 1-5 mm/s in its bulk for long (measured to 0.6 s) that does not change phi
/// (seed 1: 0.6452 at 0.3 s, 0.6455 at 0.4 s). A bed still landing moves at
/// 0.1-1 m/s. The bound is 5 % of the speed of a fall through one diameter.
inline double settled_speed() { return 0.05 * std::sqrt(2 * 9.81 * 0.001); }

inline PourResult pour_spheres(double mu, const PourConfig& c) {
  const std::string path = std::string(GRAINS_SOURCE_DIR) + "/cases/pour_spheres/case.yaml";
  std::ostringstream w, top, dom, fr;
  w.precision(12);
  auto v3 = [](double a, double b, double cc) {
    std::ostringstream o;
    o.precision(12);
    o << "[" << a << ", " << b << ", " << cc << "]";
    return o.str();
  };
  auto s = io::make_simulation(io::load_case(
      path, {"particles.0.count=" + std::to_string(c.count), "particles.0.placement.seed=" + std::to_string(c.seed),
             "materials.0.friction=" + std::to_string(mu), "walls.2.point=" + v3(c.width, 0, 0),
             "walls.4.point=" + v3(0, c.width, 0), "particles.0.placement.region.max=" + v3(c.width, c.width, c.fill_top),
             "domain.max=" + v3(c.width + 0.001, c.width + 0.001, c.fill_top + 0.001),
             "time.end=" + std::to_string(mu == 0 ? c.end_frictionless : c.end)}));
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  run_steps(s, sc.clock.n_steps);
  const auto& p = sc.particles;
  PourResult r;
  r.n = p.n_owned();
  std::vector<postprocess::Vec3> x(p.x.begin(), p.x.begin() + p.n_owned());
  std::vector<double> rad(p.radius.begin(), p.radius.begin() + p.n_owned());
  const postprocess::Box container{postprocess::Vec3(0, 0, 0), postprocess::Vec3(c.width, c.width, 1)};
  const auto bulk = postprocess::bulk_region(x, rad, container, 0.002);  // 2 d
  r.bulk_height = bulk.hi.z() - bulk.lo.z();
  r.phi = postprocess::packing_fraction(x, rad, bulk);
  // Settled: the rms speed of the grains in the bulk region (a few grains
  // on the free surface of a frictionless bed keep sliding for long; they
  // are not part of what is measured).
  double v2 = 0;
  std::size_t nb = 0;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if ((p.x[i].array() >= bulk.lo.array()).all() && (p.x[i].array() <= bulk.hi.array()).all()) {
      v2 += p.v[i].squaredNorm();
      ++nb;
    }
  r.speed = nb > 0 ? std::sqrt(v2 / static_cast<double>(nb)) : INFINITY;
  std::cout << "pour mu = " << mu << ", N = " << c.count << ", seed " << c.seed << ": bulk phi = " << r.phi
            << " (bulk z " << bulk.lo.z() << "-" << bulk.hi.z() << " m), rms speed in it " << r.speed << " m/s\n";
  return r;
}

// --------------------------------------------------------------------- silo

/// A flat-bottomed cylindrical silo (cases/silo_discharge): spheres d = 1 mm
/// poured into a cylinder of diameter `silo_d` onto a plane whose orifice is
/// closed (hole radius 0) during the fill; then, from copies of the settled
/// state, the orifice is opened to each diameter D and the mass above the
/// bottom is followed in time.
struct SiloConfig {
  int count = 6000;
  double silo_d = 0.020;    // m
  double fill_top = 0.071;  // top of the fill region (a square inscribed in the cylinder)
  double fill_end = 0.3;    // s: pour (0.12 s) and settle
  double transient = 0.04;  // s after opening before the rate is measured (the flow
                            // reaches its mean within ~0.03 s)
  double window = 0.24;     // s of steady discharge measured
  int seed = 1;
  double friction = 0.5;
};

struct Silo {
  io::Simulation sim;
  double phi_bulk = 0, bed_height = 0, speed = 0;
};

inline Silo fill_silo(const SiloConfig& c) {
  const std::string path = std::string(GRAINS_SOURCE_DIR) + "/cases/silo_discharge/case.yaml";
  const double R = c.silo_d / 2, half = R / std::sqrt(2.0) - 0.00065;
  Silo out{io::make_simulation(io::load_case(
      path, {"particles.0.count=" + std::to_string(c.count), "particles.0.placement.seed=" + std::to_string(c.seed),
             "materials.0.friction=" + num(c.friction), "walls.0.hole_radius=0", "walls.1.radius=" + num(R),
             "walls.1.height=" + num(c.fill_top + 0.002),
             "particles.0.placement.region.min=[" + num(-half) + ", " + num(-half) + ", 0.0006]",
             "particles.0.placement.region.max=[" + num(half) + ", " + num(half) + ", " + num(c.fill_top) + "]",
             "domain.min=[" + num(-R - 0.001) + ", " + num(-R - 0.001) + ", -0.004]",
             "domain.max=[" + num(R + 0.001) + ", " + num(R + 0.001) + ", " + num(c.fill_top + 0.002) + "]",
             "time.end=" + num(c.fill_end)}))};
  auto& sc = out.sim.scene;
  out.sim.pipeline.initialize(sc);
  run_steps(out.sim, sc.clock.n_steps);
  const auto& p = sc.particles;
  out.speed = mean_speed(sc);
  double ztop = 0;
  std::vector<double> zs;
  for (std::size_t i = 0; i < p.n_owned(); ++i) zs.push_back(p.x[i].z());
  std::sort(zs.begin(), zs.end());
  ztop = zs[zs.size() * 99 / 100];  // the free surface, robust to a few loose grains
  out.bed_height = ztop;
  // Bulk density: a square column within the cylinder, 2 d from the wall,
  // 2 d above the floor, 2 d below the surface (exact sphere-box volumes).
  std::vector<postprocess::Vec3> x(p.x.begin(), p.x.begin() + p.n_owned());
  std::vector<double> rad(p.radius.begin(), p.radius.begin() + p.n_owned());
  const double h = (R - 0.002) / std::sqrt(2.0);
  const postprocess::Box box{postprocess::Vec3(-h, -h, 0.002), postprocess::Vec3(h, h, ztop - 0.002)};
  out.phi_bulk = postprocess::packing_fraction(x, rad, box);
  std::cout << "silo filled: " << p.n_owned() << " grains, bed " << ztop / 0.001 << " d high, bulk phi " << out.phi_bulk
            << ", mean speed " << out.speed << " m/s\n";
  return out;
}

struct Discharge {
  double D = 0;         // orifice diameter (m)
  double rate = 0;      // kg/s over the whole window
  double rate1 = 0, rate2 = 0;  // over its first and second halves
  std::size_t left = 0;  // grains above the bottom at the end
  std::vector<double> t, m;     // the mass above the bottom against time
};

/// Opens the orifice of a copy of the filled silo to diameter D and measures
/// the mass flow rate: minus the least-squares slope of the mass above the
/// bottom plane against time (sampled every 2 ms) in the steady window.
inline Discharge discharge(const Silo& filled, double D, const SiloConfig& c) {
  const std::string path = std::string(GRAINS_SOURCE_DIR) + "/cases/silo_discharge/case.yaml";
  io::Simulation s = io::make_simulation(io::Case(filled.sim.c));
  s.scene = filled.sim.scene;  // the settled state, continued
  s.scene.walls.of<sim::PlaneWall>()[0].hole_radius = D / 2;
  const double t0 = s.scene.clock.time;
  const std::int64_t every = std::max<std::int64_t>(1, std::llround(0.002 / s.scene.clock.dt));
  const auto steps = static_cast<std::int64_t>(std::ceil((c.transient + c.window) / s.scene.clock.dt));
  s.scene.clock.n_steps = s.scene.clock.step + steps;
  Discharge d;
  d.D = D;
  const std::pair<sim::Vec3, sim::Vec3> bottom{sim::Vec3(0, 0, 0), sim::Vec3(0, 0, 1)};
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    if (s.scene.clock.step % every == 0 && s.scene.clock.time - t0 >= c.transient) {
      d.t.push_back(s.scene.clock.time - t0);
      d.m.push_back(io::count_mass(s.scene, bottom).mass);
    }
  }
  d.left = io::count_mass(s.scene, bottom).grains;
  auto slope = [&](std::size_t a, std::size_t b) {
    return -fit_line(std::vector<double>(d.t.begin() + a, d.t.begin() + b),
                     std::vector<double>(d.m.begin() + a, d.m.begin() + b))
                .b;
  };
  const std::size_t n = d.t.size();
  d.rate = slope(0, n);
  d.rate1 = slope(0, n / 2);
  d.rate2 = slope(n / 2, n);
  std::cout << "orifice D = " << D / 0.001 << " d: W = " << d.rate * 1e3 << " g/s (halves " << d.rate1 * 1e3 << ", "
            << d.rate2 * 1e3 << "), " << d.left << " grains left\n";
  return d;
}

/// Beverloo W = C rho_b sqrt(g) (D - k d)^(5/2), fitted as the line
/// W^(2/5) = s (D - k d) with s = (C rho_b sqrt(g))^(2/5) by least squares
/// (Beverloo et al. 1961; Mankoc et al. 2007). Standard errors of C and k by
/// propagation of the line's.
struct BeverlooFit {
  double C = 0, k = 0, se_C = 0, se_k = 0, r2 = 0;
};
inline BeverlooFit fit_beverloo(const std::vector<double>& D, const std::vector<double>& W, double rho_b, double d,
                                double g = 9.81) {
  std::vector<double> y;
  for (double w : W) y.push_back(std::pow(w, 0.4));
  const LineFit f = fit_line(D, y);
  BeverlooFit b;
  const double c0 = rho_b * std::sqrt(g);
  b.C = std::pow(f.b, 2.5) / c0;
  b.se_C = 2.5 * std::pow(f.b, 1.5) / c0 * f.se_b;
  b.k = -f.a / (f.b * d);
  // k = -a/(b d): relative errors of a and b (their correlation ignored: an
  // upper estimate for D > 0, where the intercept and slope anti-correlate).
  b.se_k = std::abs(b.k) * std::hypot(f.se_a / f.a, f.se_b / f.b);
  b.r2 = f.r2;
  return b;
}

// -------------------------------------------------- adhesive deposition

/// Adhesive micro-spheres deposited one by one onto a plate without gravity
/// (cases/adhesive_deposition: R = 5 um, rho = 2500, E = 100 MPa, w = 2 x
/// surface_energy, JKR with friction 0.3 and EPSD rolling resistance 0.05
/// limited by F_n + 2 F_c). The adhesion parameter Ad = w / (2 rho U0^2 R)
/// (Liu, Li & Chen, arXiv:1511.02315) is set through the deposition speed
/// U0 at fixed w, so the grains' deformation at rest (a0 / R* = 0.14 at
/// w = 0.01) is the same at every Ad; the stream is equally dilute at every
/// U0 (2 grains per 2 um of fall). Without gravity, grains that rebound
/// from the deposit (low Ad) leave through the open top.
// Seed-to-seed standard deviation of the bulk packing fraction of one CI
// deposit (2,000 grains, 15 d x 15 d): measured 2026-11-26 over seeds 1-3
// at Ad = 0.1, 1 and 10 (largest spread 0.005, at Ad = 10); checked by
// PackingLong.AdhesiveDepositionSweep over two seeds of its larger deposits.
constexpr double kDepositSigma = 0.004;

struct DepositConfig {
  int count = 2000;             // grains inserted, 2 at a time
  double work_of_adhesion = 0.01;  // w (J/m^2)
  double width = 0.0001;        // periodic box side (m), 10 d
  int seed = 1;
};
struct DepositResult {
  double ad = 0, u0 = 0, phi = 0, z = 0, speed = 0, bulk_height = 0;
  double phi_change = 0, z_change = 0;  // over the last 1e-4 / U0 (the last fall of 10 d)
  std::size_t n = 0, n_bulk = 0;
};

/// The frame with the periodic images (x and y, side `w`) of the spheres
/// within `reach` of a side appended after the originals.
inline postprocess::Frame with_xy_images(const postprocess::Frame& f, double w, double reach) {
  postprocess::Frame g = f;
  for (std::size_t i = 0; i < f.x.size(); ++i)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        if (dx == 0 && dy == 0) continue;
        const postprocess::Vec3 y = f.x[i] + postprocess::Vec3(dx * w, dy * w, 0);
        if (y.x() < -reach || y.x() > w + reach || y.y() < -reach || y.y() > w + reach) continue;
        g.x.push_back(y);
        g.radius.push_back(f.radius[i]);
      }
  return g;
}

inline DepositResult measure_deposit(const sim::Scene& sc, const DepositConfig& c, double ad, double u0);

inline DepositResult deposit_adhesive(double ad, const DepositConfig& c) {
  const std::string path = std::string(GRAINS_SOURCE_DIR) + "/cases/adhesive_deposition/case.yaml";
  const double rho = 2500, R = 5e-6;
  const double u0 = std::sqrt(c.work_of_adhesion / (2 * rho * R * ad));
  // As the case says: 2 grains per 2 um of fall, a fall of 55-59 d, and
  // time for the last grains to land and come to rest.
  const double every = 2e-6 / u0, end = every * (c.count / 2) + 6.5e-4 / u0;
  auto s = io::make_simulation(io::load_case(
      path, {"materials.0.surface_energy=" + num(c.work_of_adhesion / 2), "insert.0.velocity=[0, 0, " + num(-u0) + "]",
             "insert.0.every=" + num(every), "insert.0.times=" + std::to_string(c.count / 2),
             "insert.0.seed=" + std::to_string(c.seed), "time.end=" + num(end),
             "domain.max=[" + num(c.width) + ", " + num(c.width) + ", 0.0006]",
             "insert.0.region.max=[" + num(c.width) + ", " + num(c.width) + ", 0.00059]"}));
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  // The deposit is measured twice, 1e-4 / U0 apart, to show it has come to
  // rest: its structure no longer changes. (The grains keep a small
  // vibration, about 5 mm/s rms whatever U0, with no change of contacts: the
  // EPSD rolling spring has no dashpot, and an adhesive network rocks on it.)
  run_steps(s, sc.clock.n_steps - static_cast<std::int64_t>(std::llround(1e-4 / u0 / sc.clock.dt)));
  const DepositResult before = measure_deposit(sc, c, ad, u0);
  run_steps(s, sc.clock.n_steps);
  DepositResult r = measure_deposit(sc, c, ad, u0);
  r.phi_change = r.phi - before.phi;
  r.z_change = r.z - before.z;
  std::cout << "adhesive deposition Ad = " << ad << " (U0 = " << u0 << " m/s, w = " << c.work_of_adhesion
            << " J/m^2), " << r.n << " of " << c.count << " grains in the box, seed " << c.seed
            << ": bulk phi = " << r.phi << ", Z = " << r.z << " (" << r.n_bulk << " grains, bulk height "
            << r.bulk_height << " m), rms speed there " << r.speed << " m/s; over the last 1e-4/U0 s phi changed by "
            << r.phi_change << ", Z by " << r.z_change << "\n";
  return r;
}

inline DepositResult measure_deposit(const sim::Scene& sc, const DepositConfig& c, double ad, double u0) {
  const double d = 1e-5;  // grain diameter (m)
  DepositResult r;
  r.ad = ad;
  r.u0 = u0;
  const auto f = sphere_frame(sc);
  r.n = f.x.size();
  // Bulk: the whole periodic cross-section (with the spheres' images), 2 d
  // above the plate and 3 d below the free surface (the mean height of the
  // top 5 % of centres: the surface of a loose deposit is ragged).
  const double reach = sc.neighbors.reach();
  const auto g = with_xy_images(f, c.width, d + reach);
  const postprocess::Box box{postprocess::Vec3(0, 0, 0), postprocess::Vec3(c.width, c.width, 1)};
  postprocess::Box bulk = postprocess::bulk_region(f.x, f.radius, box, 2 * d);
  bulk.lo = postprocess::Vec3(0, 0, 2 * d);
  bulk.hi = postprocess::Vec3(c.width, c.width, bulk.hi.z() + 2 * d - 3 * d);
  r.bulk_height = bulk.hi.z() - bulk.lo.z();
  r.phi = postprocess::packing_fraction(g.x, g.radius, bulk);
  // Contacts: touching or held in tension by JKR (up to the pull-off
  // separation, the neighbour lists' reach); the images only as partners.
  postprocess::ContactOptions co;
  co.gap = reach;
  const auto contacts = postprocess::find_contacts(g, co);
  const auto units = postprocess::units_of(g);
  postprocess::Box sel = bulk;
  sel.lo.x() = sel.lo.y() = 0;
  sel.hi.x() = sel.hi.y() = c.width * (1 - 1e-12);  // originals lie in [0, w)
  const auto coord = postprocess::coordination(g, units, contacts, sel);
  r.z = coord.mean_z;
  r.n_bulk = coord.n_selected;
  // At rest: the rms speed of the grains in the bulk region.
  double v2 = 0;
  std::size_t nb = 0;
  for (std::size_t i = 0; i < r.n; ++i) {
    if (f.x[i].z() >= bulk.lo.z() && f.x[i].z() <= bulk.hi.z()) {
      v2 += sc.particles.v[i].squaredNorm();
      ++nb;
    }
  }
  r.speed = nb ? std::sqrt(v2 / static_cast<double>(nb)) : INFINITY;
  return r;
}

// ----------------------------------------------------------------- jamming

/// Frictionless spheres jammed by growing radii in a periodic cube
/// (cases/jam_frictionless: d0 = 0.9 mm at the start, rho = 2500, E = 10 MPa,
/// e = 0.1; the four-phase schedule of its README: fast growth to a dense
/// agitated fluid, slow growth until it jams at an overlap per particle of
/// 2e-3, decompression to 5e-4, relaxation at fixed radii). Measured after the
/// relaxation: the kinetic energy is below 1 % of the elastic energy and the
/// total energy falls monotonically (the packing creeps slowly).
struct JamConfig {
  int count = 2000;
  double box = 0.015;  // m; fill fraction 0.23 at the start (count/box^3 kept in larger runs)
  int seed = 1;
};
struct JamResult {
  double phi = 0, z = 0, z_rigid = 0, rattlers = 0, overlap = 0, mean_rel_overlap = 0, speed = 0, scale = 0;
  double speed_rigid = 0;  // mean speed of the non-rattlers (rms)
  std::size_t n = 0;
};

/// Contacts of the periodic packing by global id (each physical pair once),
/// mean Z, and Z without rattlers (fewer than 4 contacts, removed
/// iteratively with their contacts: O'Hern et al. 2003).
inline JamResult measure_jammed(const sim::Scene& sc, double box) {
  const auto& p = sc.particles;
  const auto& nl = sc.neighbors;
  std::set<std::pair<std::int64_t, std::int64_t>> pairs;
  double rel = 0;
  const std::size_t rows = nl.row_start.size() - 1;
  for (std::size_t i = 0; i < rows; ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const auto j = nl.partner[k];
      const double rs = p.radius[i] + p.radius[j];
      const double dist = (p.x[i] - p.x[j]).norm();
      if (dist >= rs) continue;
      if (pairs.emplace(std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])).second) rel += 1 - dist / rs;
    }
  std::map<std::int64_t, std::vector<std::int64_t>> nb;
  for (std::size_t i = 0; i < p.n_owned(); ++i) nb[p.id[i]];
  for (const auto& [a, b] : pairs) {
    nb[a].push_back(b);
    nb[b].push_back(a);
  }
  JamResult r;
  r.n = p.n_owned();
  std::map<std::int64_t, int> left;
  std::set<std::int64_t> rattler;
  std::vector<std::int64_t> queue;
  double zsum = 0, vol = 0;
  for (const auto& [id, list] : nb) {
    left[id] = static_cast<int>(list.size());
    zsum += static_cast<double>(list.size());
    if (list.size() < 4) {
      rattler.insert(id);
      queue.push_back(id);
    }
  }
  while (!queue.empty()) {
    const auto id = queue.back();
    queue.pop_back();
    for (auto m : nb[id])
      if (!rattler.count(m) && --left[m] < 4) {
        rattler.insert(m);
        queue.push_back(m);
      }
  }
  double zr = 0;
  for (const auto& [id, list] : nb)
    if (!rattler.count(id))
      for (auto m : list) zr += rattler.count(m) ? 0 : 1;
  for (std::size_t i = 0; i < p.n_owned(); ++i) vol += 4.0 / 3.0 * M_PI * std::pow(p.radius[i], 3);
  r.phi = vol / (box * box * box);
  r.z = zsum / static_cast<double>(r.n);
  r.rattlers = static_cast<double>(rattler.size()) / static_cast<double>(r.n);
  r.z_rigid = zr / static_cast<double>(r.n - rattler.size());
  r.mean_rel_overlap = pairs.empty() ? 0 : rel / static_cast<double>(pairs.size());
  r.overlap = sim::RadiusGrowth::overlap_per_particle(sc);
  r.speed = mean_speed(sc);
  double v2 = 0;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if (!rattler.count(p.id[i])) v2 += p.v[i].squaredNorm();
  r.speed_rigid = std::sqrt(v2 / static_cast<double>(r.n - rattler.size()));
  return r;
}

inline JamResult jam(const JamConfig& c) {
  const std::string path = std::string(GRAINS_SOURCE_DIR) + "/cases/jam_frictionless/case.yaml";
  const double r0 = 0.00045;
  const std::string lo = num(r0), hi = num(c.box - r0);
  auto s = io::make_simulation(io::load_case(
      path, {"particles.0.count=" + std::to_string(c.count), "particles.0.placement.seed=" + std::to_string(c.seed),
             "particles.0.placement.region.min=[" + lo + ", " + lo + ", " + lo + "]",
             "particles.0.placement.region.max=[" + hi + ", " + hi + ", " + hi + "]",
             "domain.max=[" + num(c.box) + ", " + num(c.box) + ", " + num(c.box) + "]"}));
  sim::RadiusGrowth* g = nullptr;
  for (const auto& st : s.pipeline.stages())
    if (auto* q = dynamic_cast<sim::RadiusGrowth*>(st.get())) g = q;
  if (!g) throw std::runtime_error("cases/jam_frictionless has no radius_growth stage");
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  // Report the state at the end of each phase.
  for (const auto& ph : s.c.scene.growth.phases) {
    run_steps(s, static_cast<std::int64_t>(std::ceil(ph.until / sc.clock.dt - 1e-9)));
    const JamResult m = measure_jammed(sc, c.box);
    std::cout << "  phase (rate " << ph.rate << ", target " << ph.target_overlap << ") to t = " << sc.clock.time
              << " s: o = " << m.overlap << ", phi " << m.phi << ", Z " << m.z << ", Z without rattlers " << m.z_rigid
              << " (rattlers " << 100 * m.rattlers << " %), rms speed " << m.speed << " m/s (non-rattlers "
              << m.speed_rigid << ")\n";
  }
  run_steps(s, sc.clock.n_steps);
  JamResult r = measure_jammed(sc, c.box);
  r.scale = sc.particles.radius[0] / r0;
  std::cout << "jammed (N = " << r.n << ", seed " << c.seed << "): phi " << r.phi << ", Z " << r.z
            << ", Z without rattlers " << r.z_rigid << " (rattlers " << 100 * r.rattlers << " %), o " << r.overlap
            << ", mean overlap/(ri+rj) " << r.mean_rel_overlap << ", mean speed " << r.speed << " m/s"
            << (g->capped() ? " [growth capped]" : "") << "\n";
  if (g->capped()) ADD_FAILURE() << "radius growth hit max_scale before jamming";
  return r;
}

}  // namespace grains::test::packing
