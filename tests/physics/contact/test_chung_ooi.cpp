// The Chung & Ooi benchmark: Y.C. Chung, J.Y. Ooi, "Benchmark tests for
// verifying discrete element modelling codes at particle impact level",
// Granular Matter 13 (2011) 643-656. All eight tests, run through the real
// simulator (case text -> Simulation -> pipeline steps).
//
// Sources. The paper itself was not available. Its inputs and the digitised
// curves come from docs/dev/adhesion_sources.md section 6, which collects them
// from Kratos DEMApplication (K: benchmark mdpa files and the digitised paper
// curves applications/DEMApplication/test_examples/basic_benchmarks/paper_data/
// benchmark{4,5,6,8}_graph*.dat and tests/DEM3D_chung_ooi_tests/test{1,2}_data/
// paper_data/benchmark{1,2}_graph2.dat) and from YADE's scripts for tests
// 1-4 (Y). Every other reference number is derived here (rigid-body impact
// theory, Hertz, symmetry, scaling) and says so. Where the source is
// unverified, the comment says that as well.
//
// The model is the default: Hertz normal force with damping calibrated to
// the restitution, and when friction > 0, Mindlin's tangential spring
// k_t = 8 G* sqrt(R* d) with its dashpot and the Coulomb limit
// (sim/laws/normal_hertz.hpp, sim/laws/tangential.hpp). The "rigid" plane of
// the paper is a plane wall whose material has 1000 times the sphere's E (as
// YADE's scripts do), with the same nu, restitution and friction (pair
// values are the means of the two materials'). Its finite stiffness changes
// E* and G* by about 0.1 %; the Hertz references below use the pair's actual E*.
//
// The time step is given explicitly: the Hertz contact time of the impact
// divided by the number of steps stated in each test (at least 1000), so
// each contact is resolved with >= 1000 steps. The whole file runs in about
// a second (Release).
//
// Already covered elsewhere and not repeated here (test_normal_impact.cpp):
// test 1 for glass, maximum overlap and contact time within 0.5 % of Hertz
// and the published 274 um / 40.3 us; the calibration's restitution at
// e = 0.1, 0.5, 0.9. test_oblique_impact.cpp: Kharaz's alumina sphere on a
// glass plate (not the paper's rigid plane) in the sliding regime.
//
// Test 6 exposed a problem of the tangential spring, since fixed: with
// strong damping (e = 0.5) the friction impulse in gross sliding fell short
// of mu times the normal impulse (Test6GrossSlidingMatchesRigidBody).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

using sim::Vec3;

constexpr double kDeg = M_PI / 180;

// ---- materials: docs/dev/adhesion_sources.md section 6, "Materials used across the tests" ----
struct Material {
  const char* name;
  double E, nu, rho;
};

const Material kGlass{"glass", 48e9, 0.20, 2800};               // Y test 1
const Material kLimestone{"limestone", 20e9, 0.25, 2500};       // Y test 1
const Material kAlAlloyT2{"al_alloy", 70e9, 0.30, 2699};        // Y test 2
const Material kAlAlloy{"al_alloy", 70e9, 0.33, 2700};          // Y test 4; K tests 6-8
const Material kMgAlloy{"mg_alloy", 40e9, 0.35, 1800};          // Y test 2
const Material kAlumina{"alumina", 380e9, 0.23, 4000};          // Y and K tests 3-4
const Material kCastIron{"cast_iron", 100e9, 0.25, 7000};       // Y test 3
const Material kSteel{"steel", 208e9, 0.30, 7850};              // K test 5 (mdpa)
const Material kPolyethylene{"polyethylene", 1e9, 0.40, 1400};  // PySPH test 5 (K labels the curve)
const Material kNylon{"nylon", 2.5e9, 0.40, 1000};              // PySPH; K labels the test 6 curve

/// The paper's rigid plane (and test 8's big sphere): E (and rho) scaled.
Material scaled(const Material& m, const char* name, double E_factor, double rho_factor) {
  return {name, m.E * E_factor, m.nu, m.rho * rho_factor};
}

// ---- one impact, run as a case ----
struct Body {
  Material mat;
  double R;
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();  // initial angular velocity
};

/// Sphere a, above, falls onto sphere b (centre at the origin) or, without
/// b, onto the rigid plane z = 0 (normal +z). Both share e and mu.
struct Shot {
  Body a;
  std::optional<Body> b;
  double e = 1, mu = 0;
  int steps = 1000;  // time steps per Hertz contact time
};

struct Outcome {
  Vec3 va, wa, vb, wb;  // after the contact
  double max_overlap = 0, max_force = 0, t_peak = 0, contact_time = 0;
  bool separated = false;
};

double mass(const Body& b) { return b.mat.rho * 4.0 / 3.0 * M_PI * b.R * b.R * b.R; }

Material partner(const Shot& s) { return s.b ? s.b->mat : scaled(s.a.mat, "rigid", 1000, 1); }

/// E* and G* of the pair as the simulator mixes them (docs/physics.md).
double e_star(const Shot& s) {
  const Material a = s.a.mat, b = partner(s);
  return 1 / ((1 - a.nu * a.nu) / a.E + (1 - b.nu * b.nu) / b.E);
}
double g_star(const Shot& s) {
  const Material a = s.a.mat, b = partner(s);
  const double Ga = a.E / (2 * (1 + a.nu)), Gb = b.E / (2 * (1 + b.nu));
  return 1 / ((2 - a.nu) / Ga + (2 - b.nu) / Gb);
}

/// Hertz (Johnson 1985; REFERENCES.md): the elastic head-on impact of the
/// shot at its normal approach speed.
struct Hertz {
  double dmax, fmax, tc;
};
Hertz hertz(const Shot& s) {
  const double Estar = e_star(s);
  const double Rstar = s.b ? s.a.R * s.b->R / (s.a.R + s.b->R) : s.a.R;
  const double mstar = s.b ? mass(s.a) * mass(*s.b) / (mass(s.a) + mass(*s.b)) : mass(s.a);
  const double vn = -(s.a.v.z() - (s.b ? s.b->v.z() : 0.0));
  const double d = std::pow(15 * mstar * vn * vn / (16 * Estar * std::sqrt(Rstar)), 0.4);
  return {d, 4.0 / 3.0 * Estar * std::sqrt(Rstar) * std::pow(d, 1.5), 2.9432 * d / vn};
}

/// Runs the shot from a gap of 0.1 dmax to the end of the contact (zero
/// overlap again, interpolated) and measures it. The force is the normal
/// force on sphere a after each step.
Outcome run(const Shot& s) {
  const Hertz h = hertz(s);
  const double dt = h.tc / s.steps, gap = 0.1 * h.dmax;
  const double Ra = s.a.R, Rb = s.b ? s.b->R : 0.0;
  const double L = 2 * (Ra + Rb);
  const Material b = partner(s);
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [" << -L << ", " << -L << ", " << (s.b ? -L : -0.5 * Ra) << "], max: [" << L << ", " << L << ", "
    << 2 * L << "]}\n";
  y << "materials:\n"
    << material("a", s.a.mat.rho, s.a.mat.E, s.a.mat.nu, s.e, s.mu) << material("b", b.rho, b.E, b.nu, s.e, s.mu);
  y << "particles:\n" << single("a", "a", Vec3(0, 0, Ra + Rb + gap), Ra, s.a.v);
  if (s.b)
    y << single("b", "b", Vec3(0, 0, 0), Rb, s.b->v);
  else
    y << "walls:\n  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: b}\n";
  y << "time: {dt: " << dt << ", end: " << 50 * h.tc << "}\n";
  auto sim = from_yaml(y.str());
  auto& sc = sim.scene;
  auto& p = sc.particles;
  // Particle sets take no angular velocity key: set it before the first
  // force evaluation (initialize() computes forces only, it keeps omega).
  if (s.a.w != Vec3::Zero() || (s.b && s.b->w != Vec3::Zero())) {
    EXPECT_FALSE(p.omega.empty()) << "a spinning shot needs the rotation fields (friction > 0)";
    if (p.omega.empty()) return {};
    p.omega[index_of(p, 0)] = s.a.w;
    if (s.b) p.omega[index_of(p, 1)] = s.b->w;
  }
  sim.pipeline.initialize(sc);
  auto overlap = [&] {
    if (!s.b) return Ra - p.x[0].z();
    return Ra + Rb - (p.x[index_of(p, 0)] - p.x[index_of(p, 1)]).norm();
  };
  Outcome o;
  double prev = overlap(), t_in = -1;
  while (sc.clock.step < sc.clock.n_steps) {
    sim.pipeline.step(sc);
    const double d = overlap();
    const std::size_t ia = index_of(p, 0);
    const Vec3 n = s.b ? Vec3((p.x[ia] - p.x[index_of(p, 1)]).normalized()) : Vec3(0, 0, 1);
    const double f = p.f[ia].dot(n);
    o.max_overlap = std::max(o.max_overlap, d);
    if (f > o.max_force) {
      o.max_force = f;
      o.t_peak = sc.clock.time;
    }
    if (prev <= 0 && d > 0 && t_in < 0) t_in = sc.clock.time - dt * d / (d - prev);
    if (prev > 0 && d <= 0 && t_in >= 0) {
      o.contact_time = sc.clock.time - dt * d / (d - prev) - t_in;
      o.separated = true;
      break;
    }
    prev = d;
  }
  EXPECT_TRUE(o.separated) << "the contact did not end";
  o.t_peak -= t_in;
  const std::size_t ia = index_of(p, 0);
  o.va = p.v[ia];
  o.wa = p.omega.empty() ? Vec3(Vec3::Zero()) : p.omega[ia];
  if (s.b) {
    const std::size_t ib = index_of(p, 1);
    o.vb = p.v[ib];
    o.wb = p.omega.empty() ? Vec3(Vec3::Zero()) : p.omega[ib];
  }
  return o;
}

/// [derived] For an elastic Hertz impact the force-weighted mean overlap is
/// c dmax with c = int F d dt / (dmax int F dt) = I(5/2)/I(3/2),
/// I(p) = int_0^1 u^p (1 - u^(5/2))^(-1/2) du = 2/5 B((2p+2)/5, 1/2), so
/// c = B(7/5, 1/2)/2 = 0.8176. The simulator's lever arm on a plane is R - d
/// (the contact point is the foot of the centre on the plane,
/// contact/plane.hpp), so a friction impulse J_t spins a sphere up by
/// (R - c dmax) J_t / I rather than the rigid-body R J_t / I.
double lever_factor() { return std::tgamma(1.4) * std::tgamma(0.5) / (2 * std::tgamma(1.9)); }

// ---- test 1: elastic normal impact of two identical spheres ----
// Inputs (Y, K; adhesion_sources.md): R = 0.01 m, +-10 m/s, e = 1 (mu
// irrelevant: 0 here). Hertz (derived in the doc, recomputed here from the
// formulas): glass 274.1 um / 10.70 kN / 40.34 us, limestone 368.3 um /
// 7.11 kN / 54.2 us.
TEST(ChungOoi, Test1LimestoneSpheresFollowHertz) {
  const double R = 0.01, v = 10;
  const Shot s{Body{kLimestone, R, Vec3(0, 0, -v)}, Body{kLimestone, R, Vec3(0, 0, v)}, 1.0, 0.0, 2000};
  const Hertz h = hertz(s);
  // The doc's figures (rounded) against the formula: checks the inputs.
  EXPECT_NEAR(h.dmax, 368.3e-6, 0.1e-6);
  EXPECT_NEAR(h.fmax, 7.11e3, 0.005e3);
  EXPECT_NEAR(h.tc, 54.2e-6, 0.05e-6);
  const auto o = run(s);
  // Hertz, 0.1 %: at 2000 steps per contact the measured errors are
  // < 3e-5 (the contact time's constant 2.9432 is itself rounded).
  EXPECT_NEAR(o.max_overlap / h.dmax, 1.0, 0.001);
  EXPECT_NEAR(o.max_force / h.fmax, 1.0, 0.001);
  EXPECT_NEAR(o.contact_time / h.tc, 1.0, 0.001);
  // Elastic: the force peaks at half the contact time (measured 0.50002),
  // and the spheres leave at the speed they came with.
  EXPECT_NEAR(o.t_peak / h.tc, 0.5, 0.001);
  EXPECT_NEAR((o.vb.z() - o.va.z()) / (2 * v), -1.0, 1e-4);
}

TEST(ChungOoi, Test1GlassPeakForce) {
  // The glass overlap and contact time are in test_normal_impact.cpp; the
  // force is not.
  const double R = 0.01, v = 10;
  const Shot s{Body{kGlass, R, Vec3(0, 0, -v)}, Body{kGlass, R, Vec3(0, 0, v)}, 1.0, 0.0, 2000};
  const Hertz h = hertz(s);
  EXPECT_NEAR(h.fmax, 10.70e3, 0.005e3);  // the doc's Hertz figure
  const auto o = run(s);
  EXPECT_NEAR(o.max_force / h.fmax, 1.0, 0.001);
  EXPECT_NEAR(o.t_peak / h.tc, 0.5, 0.001);
  // The paper's curve as K digitised it (test1_data/paper_data/
  // benchmark1_graph2.dat, kN vs us): peak 10.704 kN at 20.45 us, back to
  // zero at 40.48 us. 1 %: the digitisation (points ~1 us apart near the end).
  EXPECT_NEAR(o.max_force / 10.704e3, 1.0, 0.01);
  EXPECT_NEAR(o.contact_time / 40.48e-6, 1.0, 0.01);
  EXPECT_NEAR(o.t_peak / 20.45e-6, 1.0, 0.03);  // the peak time: a flat top, +-0.5 us
}

// ---- test 2: elastic normal impact of a sphere with a rigid plane ----
// Inputs (Y, K): R = 0.1 m, 0.2 m/s, e = 1, mu = 0. Al alloy (Y: nu = 0.30,
// rho = 2699) and Mg alloy. Hertz for a truly rigid plane (the doc): Al
// 49.7 um / 11.37 kN / 732 us, Mg 52.1 um / 7.23 kN / 767 us. The plane here
// has E x 1000, which lowers E* by 0.09 %: those figures within 0.3 %.
TEST(ChungOoi, Test2SphereOnRigidPlaneFollowsHertz) {
  struct Case {
    Material m;
    double dmax, fmax, tc;  // the doc's rigid-plane Hertz values
  };
  for (const auto& c : {Case{kAlAlloyT2, 49.7e-6, 11.37e3, 732e-6}, Case{kMgAlloy, 52.1e-6, 7.23e3, 767e-6}}) {
    SCOPED_TRACE(c.m.name);
    const double R = 0.1, v = 0.2;
    const Shot s{Body{c.m, R, Vec3(0, 0, -v)}, std::nullopt, 1.0, 0.0, 2000};
    const Hertz h = hertz(s);
    const auto o = run(s);
    EXPECT_NEAR(o.max_overlap / h.dmax, 1.0, 0.001);  // as test 1: measured < 3e-5
    EXPECT_NEAR(o.max_force / h.fmax, 1.0, 0.001);
    EXPECT_NEAR(o.contact_time / h.tc, 1.0, 0.001);
    EXPECT_NEAR(o.t_peak / h.tc, 0.5, 0.001);
    EXPECT_NEAR(o.va.z() / v, 1.0, 1e-4);
    EXPECT_NEAR(o.max_overlap / c.dmax, 1.0, 0.003);
    EXPECT_NEAR(o.max_force / c.fmax, 1.0, 0.003);
    EXPECT_NEAR(o.contact_time / c.tc, 1.0, 0.003);
  }
  // The paper's Al curve as K digitised it (test2_data/paper_data/
  // benchmark2_graph2.dat, kN vs us): peak 11.357 kN at 355-373 us, zero
  // again at 727.5 us. It fits Al with nu = 0.30. 1 %: digitisation.
  const auto o = run(Shot{Body{kAlAlloyT2, 0.1, Vec3(0, 0, -0.2)}, std::nullopt, 1.0, 0.0, 2000});
  EXPECT_NEAR(o.max_force / 11.357e3, 1.0, 0.01);
  EXPECT_NEAR(o.contact_time / 727.5e-6, 1.0, 0.01);
  EXPECT_NEAR(o.t_peak, 364e-6, 12e-6);
}

// ---- test 3: normal impact with different coefficients of restitution ----
// Inputs (Y, K): sphere on a rigid plane, R = 2.5 mm, 3.9 m/s, mu = 0;
// alumina and cast iron; e swept (Y: 0.2 ... 1.0; K: 0 ... 1). Output: the
// rebound ratio -v'/v, which should equal the input e (the paper's line
// y = x). Near zero: e = 0.01 and 0.05 (e = 0 itself is refused by the
// calibration: no finite damping stops a clamped Hertz contact dead).
TEST(ChungOoi, Test3ReboundRatioEqualsInputRestitution) {
  for (const auto& m : {kAlumina, kCastIron})
    for (const double e : {0.01, 0.05, 0.2, 0.4, 0.6, 0.8, 1.0}) {
      const double v = 3.9;
      const auto o = run(Shot{Body{m, 0.0025, Vec3(0, 0, -v)}, std::nullopt, e, 0.0, 2000});
      // The calibration is exact for the ODE (sim/laws/restitution.cpp);
      // what is left is the time discretisation. Measured at 2000 steps:
      // relative error <= 6e-4 for e >= 0.2 (the largest at 0.2), absolute
      // 1e-4 at 0.05 and 5e-5 at 0.01. Bounds: 0.1 % relative for
      // e >= 0.2, 2e-4 absolute below.
      const double achieved = o.va.z() / v;
      if (e >= 0.2)
        EXPECT_NEAR(achieved / e, 1.0, 1e-3) << m.name << " e = " << e;
      else
        EXPECT_NEAR(achieved, e, 2e-4) << m.name << " e = " << e;
    }
}

// ---- test 4: oblique impact on a plane at constant speed, varying angle ----
// Inputs (Y, K): R = 2.5 mm, |v| = 3.9 m/s at theta from the normal,
// mu = 0.092, e = 0.98, no initial spin; alumina and Al alloy (70 GPa,
// 0.33, 2700), rigid plane. Outputs: e_t = v'_t/v_t (centre velocities),
// the spin omega', and the rebound angle of the contact point,
// atan((v'_t - R omega'_y)/v'_n) here (K/Y's tan^-1[(v'_t + R w')/v'_n] in
// their axes). The paper plots omega' negative (its axes); here the sphere
// moves in +x on a floor and friction spins it with omega_y > 0.
struct Oblique {
  double en, et, omega, rebound_deg;
};
Oblique oblique4(const Material& m, double theta_deg) {
  const double v = 3.9, R = 0.0025, th = theta_deg * kDeg;
  const auto o = run(Shot{Body{m, R, Vec3(v * std::sin(th), 0, -v * std::cos(th))}, std::nullopt, 0.98, 0.092, 1000});
  return {o.va.z() / (v * std::cos(th)), o.va.x() / (v * std::sin(th)), o.wa.y(),
          std::atan2(o.va.x() - R * o.wa.y(), o.va.z()) / kDeg};
}

TEST(ChungOoi, Test4SlidingRegimeMatchesRigidBodyTheory) {
  // [derived] Rigid-body impact with Coulomb friction: the contact slides
  // throughout when tan(theta) >= 7/2 mu (1 + e) (theta >= 32.5 deg); then
  // e_t = 1 - mu (1 + e)/tan(theta), omega' = 5/2 mu (1 + e) v cos(theta)/R,
  // tan(rebound) = (tan(theta) - 7/2 mu (1 + e))/e. With the simulator's
  // lever arm R - d (lever_factor()) the spin is smaller by c dmax/R:
  // 0.26 % (alumina), 0.43 % (Al alloy) at normal incidence; the references
  // below include it (with the force weighting of an elastic impact:
  // e = 0.98 is close). Measured: e_t within 4e-5, omega 1e-4, rebound
  // angle 0.004 deg, e_n 1e-6. test_oblique_impact.cpp checks a
  // glass plate at 2 %; this is the paper's rigid plane, both materials.
  const double mu = 0.092, e = 0.98, v = 3.9, R = 0.0025;
  for (const auto& m : {kAlumina, kAlAlloy}) {
    // dmax/R at the full speed; at the normal speed v cos(theta) it scales by cos^0.8.
    const double eps = hertz(Shot{Body{m, R, Vec3(0, 0, -v)}, std::nullopt}).dmax / R;
    for (double theta = 35; theta <= 85; theta += 5) {
      SCOPED_TRACE(std::string(m.name) + " theta = " + std::to_string(theta));
      const double th = theta * kDeg;
      const auto r = oblique4(m, theta);
      const double et = 1 - mu * (1 + e) / std::tan(th);
      const double w_rigid = 2.5 * mu * (1 + e) * v * std::cos(th) / R;
      const double lever = 1 - lever_factor() * eps * std::pow(std::cos(th), 0.8);
      const double reb = std::atan((std::tan(th) - mu * (1 + e) * (1 + 2.5 * lever)) / e) / kDeg;
      EXPECT_NEAR(r.en, e, 0.001 * e);
      EXPECT_NEAR(r.et, et, 5e-4);
      EXPECT_NEAR(r.omega / (w_rigid * lever), 1.0, 1e-3);
      EXPECT_NEAR(r.omega / w_rigid, 1.0, 0.006);  // the rigid-body value itself: lever arm <= 0.45 %
      EXPECT_NEAR(r.rebound_deg, reb, 0.02);
    }
  }
}

// The paper's curves as K digitised them (paper_data/benchmark4_graph1.dat:
// e_t; graph2: omega' in rad/s, negative in the paper's axes; graph3: the
// rebound angle in degrees). x is the digitised angle; we run at exactly
// that angle, so the digitisation error in x does not count against us.
struct Point {
  double x, y;
};
const std::vector<Point> kPaperEtAlumina{{5.168, 0.9481},  {10.158, 0.6870}, {14.990, 0.6244}, {20.059, 0.6161},
                                         {25.050, 0.6343}, {30.119, 0.6837}, {35.030, 0.7372}, {40.020, 0.7809},
                                         {50.000, 0.8451}, {59.980, 0.8929}, {69.960, 0.9316}, {80.020, 0.9662},
                                         {85.010, 0.9827}};
const std::vector<Point> kPaperEtAlAlloy{{5.089, 0.8987},  {10.000, 0.6713}, {15.069, 0.6129}, {20.059, 0.6087},
                                         {24.970, 0.6334}, {30.040, 0.6829}, {35.030, 0.7364}, {40.020, 0.7801},
                                         {49.921, 0.8443}, {59.980, 0.8913}, {70.040, 0.9325}, {80.099, 0.9662},
                                         {84.931, 0.9827}};
const std::vector<Point> kPaperOmegaAlumina{{4.951, -19.27},   {10.079, -213.00}, {14.970, -377.83}, {19.941, -510.55},
                                            {24.911, -599.39}, {29.961, -616.51}, {34.931, -582.26}, {39.980, -544.80},
                                            {50.000, -457.03}, {60.020, -357.49}, {69.961, -246.18}, {80.059, -126.30},
                                            {85.030, -63.15}};
const std::vector<Point> kPaperOmegaAlAlloy{{4.951, -35.32},   {9.921, -223.70},  {14.970, -389.60}, {20.020, -519.11},
                                            {24.911, -599.39}, {30.039, -617.58}, {34.852, -582.26}, {39.980, -544.80},
                                            {50.000, -458.10}, {60.020, -358.56}, {69.961, -245.11}, {80.059, -125.23},
                                            {85.030, -64.22}};
// graph3 holds the same numbers under "Al. oxide" and "Al. alloy": K
// duplicated one curve. Which material it belongs to is UNVERIFIED; our Al
// alloy follows it within 0.52 deg, our alumina within 1.04 deg.
const std::vector<Point> kPaperRebound{{4.901, 3.761},   {9.959, -1.556},  {14.935, -5.544}, {19.988, -7.538},
                                       {24.958, -7.538}, {29.922, -3.550}, {34.962, 3.429},  {39.920, 11.571},
                                       {49.834, 29.350}, {59.987, 47.795}, {69.742, 64.577}, {79.822, 78.701},
                                       {84.783, 84.517}};

/// The paper ran at 5 deg steps (K: 17 points); the digitised x scatters
/// about them by up to 0.26 deg, which near 5 deg, where e_t changes by
/// 0.05 per degree, would alone cost 0.01. We run at the nominal angle.
double nominal(double x) { return 5 * std::round(x / 5); }

TEST(ChungOoi, Test4AgreesWithThePaperAtAllAngles) {
  // Below 32.5 deg the contact sticks for part of the impact, the Mindlin
  // spring stores and returns tangential energy, and e_t rises from its
  // minimum (~0.61 at 20 deg) to ~0.9-0.95 at 5 deg (Maw et al.; the rigid
  // 5/7 does not apply). There is no closed form: the paper's curve is the
  // reference. Which code produced it is UNVERIFIED. Largest differences
  // found (at the nominal angles): alumina e_t 0.012, omega 10 rad/s,
  // rebound 1.04 deg (all at 10-15 deg); Al alloy 0.004, 4.8 rad/s,
  // 0.52 deg (5 and 70 deg). Bounds, about 1.2 times those: e_t 0.015,
  // omega 12 rad/s (2 % of its 617 rad/s peak), rebound 1.2 deg (alumina)
  // and 0.6 deg (Al alloy). Sensitivity: the 8 % between alumina's and Al
  // alloy's G*/E* (so k_t/k_n) moves e_t at 5 deg by 0.05 (0.944 against
  // 0.896 here, 0.948 against 0.899 in the paper).
  struct Set {
    Material m;
    const std::vector<Point>* et;
    const std::vector<Point>* omega;
    double rebound_tol;
  };
  for (const auto& set : {Set{kAlumina, &kPaperEtAlumina, &kPaperOmegaAlumina, 1.2},
                          Set{kAlAlloy, &kPaperEtAlAlloy, &kPaperOmegaAlAlloy, 0.6}}) {
    for (const auto& [x, y] : *set.et)
      EXPECT_NEAR(oblique4(set.m, nominal(x)).et, y, 0.015) << set.m.name << " e_t at " << x;
    for (const auto& [x, y] : *set.omega)
      EXPECT_NEAR(-oblique4(set.m, nominal(x)).omega, y, 12) << set.m.name << " omega at " << x;
    for (const auto& [x, y] : kPaperRebound)
      EXPECT_NEAR(oblique4(set.m, nominal(x)).rebound_deg, y, set.rebound_tol) << set.m.name << " rebound at " << x;
  }
}

// ---- test 5: oblique impact, constant normal velocity, varying tangential velocity ----
// Inputs (K mdpa + class; PySPH agrees): R = 10 um, v_n = 5 m/s, v_t
// varied, e = 1, mu = 0.3; steel and polyethylene on a rigid plane (no
// damping: e = 1). Outputs against Psi1 = v_t/(mu v_n): the normalised
// recoil angle Psi2 = (v'_t - R omega'_y)/(mu v'_n) (contact point) and the
// normalised spin S = -R omega'_y/(mu v_n) (the paper's sign).
struct Recoil {
  double psi2, spin, en, eps;  // eps = dmax/R (Hertz)
};
Recoil oblique5(const Material& m, double psi1) {
  const double vn = 5, R = 1e-5, mu = 0.3;
  const Shot s{Body{m, R, Vec3(mu * vn * psi1, 0, -vn)}, std::nullopt, 1.0, mu, 1000};
  const auto o = run(s);
  return {(o.va.x() - R * o.wa.y()) / (mu * o.va.z()), -R * o.wa.y() / (mu * vn), o.va.z() / vn, hertz(s).dmax / R};
}

/// [derived] Hertz-Mindlin without slip (no Coulomb limit, no damping): a
/// sphere (I = 2/5 m R^2) meets a plane with contact-point slip u0 and no
/// spin; Hertz normal force K d^(3/2), tangential spring F = -k_t xi,
/// k_t = 8 G* sqrt(R d) = 6 (G*/E*) K sqrt(d), lever arm l = R - d as the
/// simulator has it, with R = dmax/eps (eps = dmax/R of the real impact;
/// eps = 0 gives the rigid-body arm R). Integrated by RK4 in units
/// m = K = v_n = 1 (dmax = (5/4)^(2/5)). Returns u'/u0.
double no_slip_recoil(double g_over_e, double eps) {
  const double dmax = std::pow(1.25, 0.4);
  const double R = eps > 0 ? dmax / eps : 1e12;
  // state: d, d', xi, v (centre, tangential), w (omega_y)
  using State = std::array<double, 5>;
  auto rate = [&](const State& s) {
    const double d = std::max(s[0], 0.0), l = R - d;
    const double F = -6 * g_over_e * std::sqrt(d) * s[2];
    return State{s[1], -d * std::sqrt(d), s[3] - l * s[4], F, -l * F / (0.4 * R * R)};
  };
  State s{0, 1, 0, 1, 0};
  const double h = 1e-4;
  for (int k = 0; k < 1'000'000; ++k) {
    auto add = [](const State& a, const State& b, double f) {
      State r;
      for (int i = 0; i < 5; ++i) r[i] = a[i] + f * b[i];
      return r;
    };
    const State k1 = rate(s), k2 = rate(add(s, k1, h / 2)), k3 = rate(add(s, k2, h / 2)), k4 = rate(add(s, k3, h));
    State n;
    for (int i = 0; i < 5; ++i) n[i] = s[i] + h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    if (k > 0 && n[0] <= 0) {
      const double t = s[0] / (s[0] - n[0]);
      const double v = s[3] + t * (n[3] - s[3]), w = s[4] + t * (n[4] - s[4]);
      return v - R * w;
    }
    s = n;
  }
  return NAN;
}

TEST(ChungOoi, Test5RecoilAngleAndSpin) {
  const double c = lever_factor();
  for (const auto& m : {kSteel, kPolyethylene}) {
    SCOPED_TRACE(m.name);
    // (a) Gross sliding, Psi1 >= 7 [derived, rigid-body with Coulomb
    // friction, e = 1]: the friction impulse is mu 2 m v_n, so
    // Psi2 = Psi1 - 2 - 5 = Psi1 - 7 and S = -5/2 (1 + e) = -5. With the
    // lever arm R - d (lever_factor) the spin is -5 (1 - c dmax/R) and Psi2
    // higher by 5 c dmax/R: 0.026 (steel, dmax/R = 0.65 %), 0.109
    // (polyethylene, 2.7 %). Measured: equal to 1e-7.
    for (const double psi1 : {7.0, 8.0, 10.0, 13.0, 20.0}) {
      const auto r = oblique5(m, psi1);
      EXPECT_NEAR(r.en, 1.0, 1e-4);
      EXPECT_NEAR(r.spin, -5 * (1 - c * r.eps), 0.001) << "Psi1 = " << psi1;
      EXPECT_NEAR(r.psi2, psi1 - 7 + 5 * c * r.eps, 0.001) << "Psi1 = " << psi1;
    }
    // The paper's points on the sliding line (K benchmark5_graph1.dat:
    // steel (9.988, 3.013), (12.961, 6.013); polyethylene (10, 3),
    // (12.961, 6.013)); they lie on Psi1 - 7 within 0.02 (digitisation), so
    // the bound is that plus our lever-arm offset.
    const double eps = oblique5(m, 10).eps;
    const std::vector<Point> paper = m.name == std::string("steel")
                                         ? std::vector<Point>{{9.988, 3.013}, {12.961, 6.013}}
                                         : std::vector<Point>{{10.0, 3.0}, {12.961, 6.013}};
    for (const auto& [x, y] : paper) EXPECT_NEAR(oblique5(m, x).psi2, y, 0.02 + 5 * c * eps) << "paper at " << x;
    // Spin from the paper (K benchmark5_graph2.dat, Psi1 >= 6): steel
    // -5.006, -5.004, -4.991 at 6, 10, 20; polyethylene -4.958, -4.963,
    // -4.942. Bound: 0.02 (digitisation) plus our lever-arm offset.
    for (const double psi1 : {6.0, 10.0, 20.0})
      EXPECT_NEAR(oblique5(m, psi1).spin, -5.0, 0.02 + 5 * c * eps) << "paper spin at " << psi1;
  }
}

TEST(ChungOoi, Test5ShapeBelowTheSlidingLine) {
  for (const auto& m : {kSteel, kPolyethylene}) {
    SCOPED_TRACE(m.name);
    std::vector<Point> curve;
    for (double psi1 = 0.5; psi1 <= 7.0001; psi1 += 0.25) curve.push_back({psi1, oblique5(m, psi1).psi2});
    for (const auto& [psi1, psi2] : curve) {
      // Coulomb [derived]: |J_t| <= mu J_n, so Psi2 >= Psi1 - 7 for every
      // Psi1 (our lever arm only raises Psi2). 1e-3: rounding.
      EXPECT_GE(psi2, psi1 - 7 - 1e-3) << "Psi1 = " << psi1;
      // Negative recoil for 2 <= Psi1 <= 6: every digitised curve has it
      // (K benchmark5_graph1.dat: steel, polyethylene and the paper's FEM
      // curve; the FEM's origin is UNVERIFIED). Ours: <= -0.3 there.
      if (psi1 >= 2 && psi1 <= 6) {
        EXPECT_LT(psi2, 0.0) << "Psi1 = " << psi1;
      }
    }
    // The minimum of the recoil: the paper's steel and polyethylene curves
    // have it at Psi1 = 4.0 (-2.79, -2.93), its FEM curve at ~4.4-4.8
    // (-1.72). Ours (steel -1.49 at 4.5, polyethylene -1.65 at 4.25) sits
    // nearer the FEM. Bounds: the position within [3.5, 5.5] and the value
    // within [-3, -1]; a model without elastic tangential reversal (rigid
    // stick) has no negative minimum at all and fails.
    const auto lowest = *std::min_element(curve.begin(), curve.end(), [](auto a, auto b) { return a.y < b.y; });
    EXPECT_GE(lowest.x, 3.5);
    EXPECT_LE(lowest.x, 5.5);
    EXPECT_GE(lowest.y, -3.0);
    EXPECT_LE(lowest.y, -1.0);
    // Joined to the sliding line by Psi1 = 6: the paper's steel curve gives
    // -1.013 (line: -1), its FEM curve -1.20 at 5.76 (line -1.24). 0.03 on
    // top of our lever-arm offset; ours: steel 0.012 above, polyethylene on it.
    const auto six = oblique5(m, 6.0);
    EXPECT_NEAR(six.psi2, -1 + 5 * lever_factor() * six.eps, 0.03);
  }
}

TEST(ChungOoi, Test5NoSlipLimitMatchesHertzMindlinTheory) {
  // Small Psi1: the contact sticks except at its very start and end, and
  // the result is the no-slip Hertz-Mindlin problem [derived:
  // no_slip_recoil]. With the rigid-body arm R it gives Psi2/Psi1 = 0.955
  // (steel, nu = 0.3) and 0.805 (polyethylene, 0.4); with the simulator's
  // arm R - d 0.9445 and 0.742 (the phase of the tangential oscillation at
  // separation is sensitive to it). Measured at Psi1 = 0.05: within 1.5e-3.
  //
  // UNVERIFIED: the paper's digitised DEM curves go the other way
  // (Psi2/Psi1 ~ -0.8 for both materials, K benchmark5_graph1.dat) and its
  // FEM curve gives ~ -0.1. A slope of -0.8 for both nu looks (a guess) like a
  // tangential spring in a fixed ratio to the normal one (k_t/k_n = 2/7
  // reverses the contact point fully). The paper's own test 4 curve at
  // 5 deg (Psi1 = 0.95, alumina) gives +0.75 - consistent with Mindlin, and
  // with us (test 4 above). So the test 5 curve's model is unknown, and
  // this test checks the theory instead.
  for (const auto& m : {kSteel, kPolyethylene}) {
    const double psi1 = 0.05;
    const Shot s{Body{m, 1e-5, Vec3(0.3 * 5 * psi1, 0, -5)}, std::nullopt, 1.0, 0.3, 1000};
    const double g_over_e = g_star(s) / e_star(s);
    const auto r = oblique5(m, psi1);
    EXPECT_NEAR(r.psi2 / psi1, no_slip_recoil(g_over_e, r.eps), 0.005) << m.name;
    // The rigid-body-arm values, for the record of the comment above.
    EXPECT_NEAR(no_slip_recoil(g_over_e, 0), m.nu < 0.35 ? 0.955 : 0.805, 0.002) << m.name;
  }
}

// ---- test 6: sphere on a plane, constant normal velocity, varying initial spin ----
// Inputs (K class + mdpa): R = 0.1 m, v_n = 0.2 m/s, no tangential centre
// velocity, spin giving the contact point V_st = v_n tan(theta),
// theta = 5 ... 85 deg; mu = 0.4, e = 0.5; Al alloy and nylon; rigid
// plane. Output: beta = -V'_st/V_st (K's sign) against
// chi = 7/2 mu (1 + e) v_n/V_st = 2.1/tan(theta). (The paper's second plot,
// tan(recoil) against tan(incident), is beta in other units; K's digitised
// x range for it does not match tan(theta) = 0.09 ... 11.4 - UNVERIFIED -
// and it is not checked.)
struct SpinResult {
  double beta, en, chi;
};
SpinResult spin6(const Material& m, double chi) {
  const double vn = 0.2, R = 0.1, mu = 0.4, e = 0.5;
  const double Vst = 3.5 * mu * (1 + e) * vn / chi;
  // omega_y = -V/R: the contact point (at -R z) moves in +x at V.
  const auto o = run(Shot{Body{m, R, Vec3(0, 0, -vn), Vec3(0, -Vst / R, 0)}, std::nullopt, e, mu, 1000});
  return {-(o.va.x() - R * o.wa.y()) / Vst, o.va.z() / vn, chi};
}
std::vector<double> chis() {  // theta = 5, 10, ..., 85 deg
  std::vector<double> c;
  for (int th = 5; th <= 85; th += 5) c.push_back(2.1 / std::tan(th * kDeg));
  return c;
}

/// Test 8's run (see there): sphere 1 (Al alloy, R = 0.1 m) spun as in
/// test 6 onto sphere 2 (R = 0.5 m, rho and E x 1000) at rest. Returns beta
/// of the contact point's slip (sphere 2 moves ~1e-6 of it) and checks the
/// normal restitution and the Coulomb bound on the way.
double beta8(double chi) {
  const double vn = 0.2, R = 0.1, R2 = 0.5;
  const double V = 3.5 * 0.4 * 1.5 * vn / chi;
  const Material big = scaled(kAlAlloy, "al_x1000", 1000, 1000);
  const auto o = run(Shot{Body{kAlAlloy, R, Vec3(0, 0, -vn), Vec3(0, -V / R, 0)}, Body{big, R2}, 0.5, 0.4, 1000});
  const double beta = -((o.va.x() - o.vb.x()) - R * o.wa.y() - R2 * o.wb.y()) / V;
  EXPECT_NEAR((o.va.z() - o.vb.z()) / vn, 0.5, 0.001) << "chi = " << chi;
  EXPECT_LE(beta, chi - 1 + 1e-3) << "Coulomb, chi = " << chi;
  return beta;
}

TEST(ChungOoi, Test6SpinOnAPlane) {
  for (const auto& m : {kAlAlloy, kNylon}) {
    SCOPED_TRACE(m.name);
    double top = -1;
    for (const double chi : chis()) {
      const auto r = spin6(m, chi);
      EXPECT_NEAR(r.en, 0.5, 0.001) << "chi = " << chi;  // measured 0.4999
      // Coulomb [derived]: the friction impulse changes the slip by at most
      // chi V_st, so -1 - chi <= beta <= chi - 1 (rigid-body arm; ours
      // shortens it by < 0.1 %).
      EXPECT_LE(r.beta, chi - 1 + 1e-3) << "chi = " << chi;
      EXPECT_GE(r.beta, -1 - chi - 1e-3) << "chi = " << chi;
      if (chi > 1 && chi < 3) top = std::max(top, r.beta);
    }
    // The contact point recoils (beta > 0) somewhere in 1 < chi < 3: the
    // paper's Al and nylon curves peak at +0.12 (chi ~ 1.45, K
    // benchmark6_graph1.dat); rigid-body theory (beta = 0 there) has no
    // such hump. Ours peaks at +0.15 (Al) and +0.16 (nylon) at chi = 1.45;
    // beyond chi ~ 3 the paper's curve falls further (Al -0.34 at chi = 24,
    // ours -0.04): the stick phase depends on the tangential dashpot, which
    // the paper's code chose in a way that is UNVERIFIED (ours damps the
    // tangential spring as the normal one), so it is not asserted.
    EXPECT_GT(top, 0.05);
  }
}

// In gross sliding (chi < 1) rigid-body theory with Coulomb friction gives
// beta = chi - 1 exactly [derived: the friction impulse mu (1 + e) m v_n
// reduces the slip by 7/2 of it over m]; the paper's digitised Al and nylon
// curves agree within 0.008 at the nominal angles (K
// benchmark6_graph1.dat). This test found a fault of the tangential spring
// (sim/laws/tangential.hpp): while sliding the spring was reset to
// xi = -(F_t + eta v_t)/k_t, so that spring and dashpot together gave the
// Coulomb force. At the start of a damped contact the dashpot alone exceeds
// the Coulomb limit (eta v_t / (mu F_n) -> 2 sqrt(G*/E*) v_t/(mu v_n) as
// d -> 0, ~4.8 here), so xi was set against the slip; then k_t ~ d^(1/2)
// grows faster than eta ~ d^(1/4) and the spring's push outgrew the dashpot:
// F_t turned to aid the slip, and the friction impulse was 73-88 % of
// mu times the normal impulse at e = 0.5 (beta = -0.26 at chi = 0.98 where
// theory says -0.02). Now the spring alone carries the Coulomb force while
// sliding; beta = chi - 1 to 5e-4.
TEST(ChungOoi, Test6GrossSlidingMatchesRigidBody) {
  for (const auto& m : {kAlAlloy, kNylon})
    for (const double chi : chis()) {
      // 0.005: our lever arm (dmax/R = 5e-4 Al, 1.2e-3 nylon) moves beta
      // by < 1e-3.
      if (chi < 1) {
        EXPECT_NEAR(spin6(m, chi).beta, chi - 1, 0.005) << m.name << " chi = " << chi;
      }
    }
  // Test 8 follows test 6 (asserted in Test8BigSphereActsAsThePlaneOfTest6);
  // here against the theory directly.
  for (const double chi : chis()) {
    if (chi < 1) {
      EXPECT_NEAR(beta8(chi), chi - 1, 0.005) << "test 8, chi = " << chi;
    }
  }
  // The paper's points below chi = 1, run at the nominal chi of the 5 deg
  // grid they were computed at (the digitised chi is off by up to 0.018).
  // 0.015: the digitisation (those points sit within 0.008 of chi - 1).
  auto nominal_chi = [](double x) { return 2.1 / std::tan(5 * kDeg * std::round(std::atan(2.1 / x) / (5 * kDeg))); };
  for (const auto& [chi, beta] : std::vector<Point>{
           {0.1762, -0.8200}, {0.3524, -0.6335}, {0.5507, -0.4447}, {0.7709, -0.2428}, {0.9692, -0.0277}})
    EXPECT_NEAR(spin6(kAlAlloy, nominal_chi(chi)).beta, beta, 0.015) << "Al, paper at chi = " << chi;
  for (const auto& [chi, beta] : std::vector<Point>{
           {0.1762, -0.8244}, {0.3744, -0.6379}, {0.5727, -0.4425}, {0.7489, -0.2428}, {0.9692, -0.0255}})
    EXPECT_NEAR(spin6(kNylon, nominal_chi(chi)).beta, beta, 0.015) << "nylon, paper at chi = " << chi;
}

// ---- test 7: two identical spheres, constant normal velocity, varying spin ----
// Inputs (K class + mdpa): R = 0.1 m, +-0.2 m/s head-on, e = 0.5, mu = 0.4,
// Al alloy; K gives the spheres equal and opposite omega about the same
// axis, omega = (v/R) tan(theta), theta = 5 ... 85 deg, and expects
// v'_t = 0 and omega' = omega (K benchmark7 data: "by symmetry"). Whether
// the paper uses this spin sense is UNVERIFIED (adhesion_sources.md).
TEST(ChungOoi, Test7CoMovingSurfacesFeelNoFriction) {
  // omega_a = +w y, omega_b = -w y, a above b: both contact points move at
  // -R w x, so there is no slip, no tangential force and no torque at all
  // [derived]: the spins and the zero tangential velocities must survive
  // exactly (to rounding).
  const double vn = 0.2, R = 0.1;
  for (int th = 5; th <= 85; th += 5) {
    const double w = vn / R * std::tan(th * kDeg);
    const auto o = run(Shot{Body{kAlAlloy, R, Vec3(0, 0, -vn), Vec3(0, w, 0)},
                            Body{kAlAlloy, R, Vec3(0, 0, vn), Vec3(0, -w, 0)}, 0.5, 0.4, 1000});
    EXPECT_NEAR(o.va.x() / vn, 0.0, 1e-12) << "theta = " << th;
    EXPECT_NEAR(o.vb.x() / vn, 0.0, 1e-12) << "theta = " << th;
    EXPECT_NEAR(o.wa.y() / w, 1.0, 1e-12) << "theta = " << th;
    EXPECT_NEAR(o.wb.y() / w, -1.0, 1e-12) << "theta = " << th;
    EXPECT_NEAR((o.va.z() - o.vb.z()) / (2 * vn), 0.5, 0.001) << "theta = " << th;
  }
}

TEST(ChungOoi, Test7SameSenseSpinIsTest6AgainstARigidPlane) {
  // The other sense, omega_a = omega_b = w y: the surfaces slide at 2 R w.
  // [derived] By the symmetry of the pair (a half-turn about the spin axis
  // swaps the spheres) the outcome is symmetric, v'_a,x = -v'_b,x and
  // omega'_a = omega'_b, and the contact plane stays still. Each sphere
  // then meets it exactly as test 6's sphere meets an infinitely stiff
  // plane with slip R w: the pair's E* and G* are half the sphere-plane
  // ones, R* = R/2, m* = m/2 and the pair's overlap and slip are twice each
  // sphere's, so forces, damping and lever arms (R - d/2 of the pair's d)
  // coincide term by term. So beta of the pair's slip must equal test 6's
  // beta at the same chi; the only difference is test 6's plane at
  // E x 1000 (0.1 % in E* and G*). Bound 0.002 (measured <= 1.6e-4).
  const double vn = 0.2, R = 0.1;
  for (const double chi : chis()) {
    const double V = 3.5 * 0.4 * 1.5 * vn / chi, w = V / R;
    const auto o = run(Shot{Body{kAlAlloy, R, Vec3(0, 0, -vn), Vec3(0, w, 0)},
                            Body{kAlAlloy, R, Vec3(0, 0, vn), Vec3(0, w, 0)}, 0.5, 0.4, 1000});
    EXPECT_NEAR((o.va.x() + o.vb.x()) / vn, 0.0, 1e-12) << "chi = " << chi;
    EXPECT_NEAR((o.wa.y() - o.wb.y()) / w, 0.0, 1e-12) << "chi = " << chi;
    const double slip0 = -2 * R * w;  // v_a - v_b - R (w_a + w_b) along x
    const double slip1 = (o.va.x() - o.vb.x()) - R * (o.wa.y() + o.wb.y());
    EXPECT_NEAR(-slip1 / slip0, spin6(kAlAlloy, chi).beta, 0.002) << "chi = " << chi;
  }
}

// ---- test 8: two differently sized spheres, constant normal velocity, varying spin ----
// Inputs (K class + mdpa): sphere 1 Al alloy, R = 0.1 m, v_n = 0.2 m/s,
// spun as in test 6; sphere 2 R = 0.5 m at rest with rho and E x 1000 (K;
// the paper's sphere 2 material is UNVERIFIED). mu = 0.4, e = 0.5.
// Outputs: beta against chi, as in test 6.
TEST(ChungOoi, Test8BigSphereActsAsThePlaneOfTest6) {
  // [derived] The Hertz-Mindlin impact is self-similar: with t scaled by
  // the Hertz time and lengths by its overlap, beta depends only on chi, e,
  // G*/E* and the sphere's I/(m R^2) - not on R*, E* or the speed. Sphere 2
  // (1.4e6 kg, E x 1000) makes m*, E* and G* those of test 6's plane to
  // 1e-5 and 0.1 %; only R* differs (0.083 m instead of 0.1 m). So beta must
  // match test 6 at every chi. The paper (K benchmark8_graph1.dat) shows its
  // cases A and B and test 6 coinciding for chi <~ 5.8 and differing above
  // (at chi = 24: A -0.318, B -0.106, test 6 -0.339; what separates A
  // from B is UNVERIFIED); we hold the whole range to 0.003 (measured
  // <= 2e-4; the lever arms R - d/2 here and R - d there differ by
  // dmax/R = 5e-4).
  for (const double chi : chis()) EXPECT_NEAR(beta8(chi), spin6(kAlAlloy, chi).beta, 0.003) << "chi = " << chi;
}

}  // namespace
}  // namespace grains::test
