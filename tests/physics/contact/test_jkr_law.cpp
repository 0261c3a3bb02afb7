// The JKR adhesive normal law (sim/laws/normal_jkr.hpp):
//  - the closed-form inverse of Johnson's overlap relation, on the whole
//    stable branch and in the weak-adhesion (Hertz) limit;
//  - a contact driven through a loading and unloading cycle follows
//    Johnson's parametric solution (F/F_c = x^3 - 2 x^(3/2),
//    d/d_c = 3 x^2 - 4 x^(1/2), solved here by bisection, independently of
//    the law): no force on approach, -8/9 F_c on touching, -F_c at
//    d = -d_c, held down to d_f = -3^(2/3) d_c, then let go;
//  - without adhesion it is the Hertz law, bit for bit;
//  - pull-off force 3/2 pi w R*: a sphere held to a plane wall pulled away by
//    a body force of 99.5 % of it stays, at 100.5 % it leaves (the issue's
//    0.5 %), also with a neighbour skin far below the pull-off separation
//    (the lists' reach), and so against a cylinder and a triangle mesh;
//  - a two-sphere collision without damping sticks below the sticking
//    velocity v_s = sqrt(2 W / m*), W the work of Johnson's curve between
//    touching and the break (the energy balance of Thornton & Ning 1998; see
//    the CriticalSticking test for their constant), bounces above it, and
//    conserves energy: v_out^2 = v_in^2 - v_s^2.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "sim/laws/contact_law.hpp"
#include "tests/physics/contact/impact.hpp"

namespace grains::test {
namespace {

using sim::JkrCurve;

constexpr double E = 1e7, nu = 0.3, rho = 2500, R = 0.001;
const double mass = rho * 4.0 / 3.0 * M_PI * R * R * R;
const double x_f = 1.0 / JkrCurve::kBreak;  // 3^(-2/3)

// Johnson's scales of a pair: F_c, d_c (a positive magnitude).
struct Scales {
  double Fc, dc;
};
Scales scales(double w, double Estar, double Rstar) {
  const double ac = std::cbrt(9 * M_PI * w * Rstar * Rstar / (8 * Estar));
  return {1.5 * M_PI * w * Rstar, ac * ac / (3 * Rstar)};
}
double johnson_F(double x) { return x * x * x - 2 * std::pow(x, 1.5); }
double johnson_d(double x) { return 3 * x * x - 4 * std::sqrt(x); }
// x on the stable branch (x >= x_f) for a scaled overlap dh, by bisection.
double johnson_x(double dh) {
  double lo = x_f, hi = 2.0;
  while (johnson_d(hi) < dh) hi *= 2;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (johnson_d(mid) < dh ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(JkrCurve, InvertsJohnsonsOverlapOnTheStableBranch) {
  for (double x = x_f; x < 1e4; x *= 1.01) {
    const double got = JkrCurve::x_of(johnson_d(x));
    // The inverse is ill-conditioned at the vertical tangent x_f (dd/dx = 0):
    // there a rounding of the overlap moves x by its square root.
    const double tol = x < 0.6 ? 1e-6 : 1e-11;
    ASSERT_NEAR(got, x, tol * x) << "x = " << x;
  }
  EXPECT_NEAR(JkrCurve::x_of(-1.0), 1.0, 1e-12) << "load-controlled pull-off";
  EXPECT_NEAR(JkrCurve::x_of(0.0), std::pow(4.0 / 3.0, 2.0 / 3.0), 1e-12) << "first touch";
  EXPECT_NEAR(JkrCurve::x_of(std::pow(2.0, 4.0 / 3.0)), std::pow(2.0, 2.0 / 3.0), 1e-12) << "zero load";
  EXPECT_NEAR(JkrCurve::x_of(-JkrCurve::kBreak), x_f, 1e-7) << "the break";
  // Newton from the last step's root (the law's path once a contact holds),
  // from above and below, lands on the closed form's root.
  for (double x = 1.2 * x_f; x < 1e3; x *= 1.1)
    for (const double start : {0.9, 0.999, 1.001, 1.3}) {
      const double u = std::sqrt(x), A = johnson_d(x) / 3.0, B = 4.0 / 3.0;
      ASSERT_NEAR(JkrCurve::root_from(start * u, A, B), JkrCurve::root(A, B), 1e-11 * u) << x << " " << start;
    }
  // Weak adhesion (d >> d_c): the overlap relation holds to rounding (no cancellation).
  for (double dh : {1e2, 1e4, 1e6, 1e8, 1e10, 1e12})
    EXPECT_NEAR(johnson_d(JkrCurve::x_of(dh)), dh, 1e-13 * dh) << "dh = " << dh;
}

// A pair of equal spheres (R* = R/2) of a case with model jkr.
struct Pair {
  io::Simulation sim;
  const sim::PairParams& p() const { return sim.scene.pairs(0, 0); }
};
Pair jkr_pair(double g, double e) {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-1, -1, -1], max: [1, 1, 1]}\nmaterials:\n  - {name: m, density: " << rho
    << ", youngs_modulus: " << E << ", poisson_ratio: " << nu << ", restitution: " << e
    << ", surface_energy: " << g << "}\ncontact: {model: jkr, tangential: none}\nparticles:\n"
    << single("p", "m", sim::Vec3::Zero(), R, sim::Vec3::Zero()) << "time: {dt_rayleigh: 0.1, end: 1e-6}\n";
  return {from_yaml(y.str())};
}

TEST(JkrLaw, CycleFollowsJohnsonsCurveWithItsHysteresis) {
  using Law = sim::ContactLaw<sim::JkrNormal, sim::NoTangential, sim::NoRolling, sim::NoCohesion>;
  static_assert(Law::history_size == 1, "the contact state alone");
  const auto pair = jkr_pair(0.05, 1.0);  // no damping: the elastic curve
  const double w = 0.1, Rs = R / 2, Es = E / (2 * (1 - nu * nu));
  const auto [Fc, dc] = scales(w, Es, Rs);
  double state = 0;
  auto force = [&](double d) {
    contact::ContactGeometry g;
    g.normal = sim::Vec3(1, 0, 0);
    g.overlap = d;
    g.radius = Rs;
    return Law::evaluate(g, sim::Vec3::Zero(), sim::Vec3::Zero(), mass / 2, pair.p(), 1e-7, &state).force.x();
  };
  // Approach: nothing until the surfaces touch.
  for (double dh = -3; dh < 0; dh += 0.01) ASSERT_EQ(force(dh * dc), 0.0) << dh;
  EXPECT_EQ(state, 0.0);
  EXPECT_NEAR(force(0.0), -8.0 / 9.0 * Fc, 1e-12 * Fc) << "the jump in on touching";
  EXPECT_GT(state, 0.0);
  double worst = 0;
  for (double dh = 0; dh <= 20; dh += 0.01) {  // loading
    const double x = johnson_x(dh);
    worst = std::max(worst, std::abs(force(dh * dc) - Fc * johnson_F(x)));
  }
  for (double dh = 20; dh > -JkrCurve::kBreak * (1 - 1e-9); dh -= 0.01) {  // unloading, into tension
    const double x = johnson_x(dh);
    worst = std::max(worst, std::abs(force(dh * dc) - Fc * johnson_F(x)));
  }
  EXPECT_LT(worst, 1e-6 * Fc) << "against Johnson's parametric solution";
  EXPECT_NEAR(force(-dc), -Fc, 1e-9 * Fc) << "the pull-off force at d = -d_c";
  EXPECT_NEAR(force(-JkrCurve::kBreak * dc * (1 - 1e-12)), -5.0 / 9.0 * Fc, 1e-4 * Fc) << "held to the break";
  EXPECT_EQ(force(-JkrCurve::kBreak * dc * (1 + 1e-9)), 0.0) << "let go beyond d_f";
  EXPECT_EQ(state, 0.0);
  EXPECT_EQ(force(-0.5 * dc), 0.0) << "no contact again before touching";
  // The break in R*: the law's reach is d_f for the pair's R*.
  EXPECT_NEAR(sim::JkrNormal::reach(Rs, pair.p()), JkrCurve::kBreak * dc, 1e-12 * dc);
  EXPECT_NEAR(JkrCurve::kBreak * dc, 0.75 * std::cbrt(M_PI * M_PI * w * w * Rs / (Es * Es)), 1e-12 * dc);
}

TEST(JkrLaw, WithoutAdhesionIsHertzExactly) {
  expect_hertz_impacts("{model: jkr, tangential: none}", E, nu, rho, R);
}

// A sphere (surface energy g, one material: w = 2 g) held to the plane x = 0
// by adhesion and pulled off along +x by a body force f F_c, F_c = 3/2 pi w R,
// starting at the equilibrium of f = 0.995 on the stable branch (negative
// overlap, near -d_c). Returns its overlap after `end` seconds.
// (Held: the final overlap is above the break -3^(2/3) d_c; torn off, it is
// well beyond it after 5 ms, having crept past the fold.)
// `wall`: the wall whose surface near the sphere is the plane x = 0 with
// normal +x (default that plane; PulledOffEveryWallKind gives the others).
const std::string kPlaneWall = "{type: plane, point: [0, 0, 0], normal: [1, 0, 0], material: m}";
double pulled(double f, double g, const std::string& neighbor = "", double end = 0.005,
              const std::string& wall = kPlaneWall, double y0 = 0) {
  const double w = 2 * g, Es = 1.0 / (2 * (1 - nu * nu) / E);
  const auto [Fc, dc] = scales(w, Es, R);
  double lo = 1, hi = 2;  // x of F/F_c = -0.995 above x = 1
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (johnson_F(mid) < -0.995 ? lo : hi) = mid;
  }
  const double d0 = dc * johnson_d(lo);
  const std::string y = pulled_case(E, nu, rho, R, g, f * Fc / mass, "{model: jkr, tangential: none}", wall, R - d0,
                                    y0, neighbor, end);
  auto s = from_yaml(y);
  auto& sc = s.scene;
  EXPECT_LT(d0, -0.5 * dc) << "the equilibrium is in tension";
  // At its equilibrium the sphere does not touch the wall (negative
  // overlap): it is held because it adhered. So it touches first: one step
  // just overlapping sets the contact state, then it is put in place at rest.
  sc.particles.x[0][0] = R - 1e-3 * dc;
  s.pipeline.initialize(sc);
  s.pipeline.step(sc);
  sc.particles.x[0][0] = R - d0;
  sc.particles.v[0].setZero();
  s.pipeline.initialize(sc);  // the forces of that place
  while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
  return R - sc.particles.x[0][0];
}

// The break of a sphere of surface energy g on the wall (R* = R).
double wall_break(double g) {
  return JkrCurve::kBreak * scales(2 * g, 1.0 / (2 * (1 - nu * nu) / E), R).dc;
}

TEST(JkrLaw, PullOffForceIsThreeHalvesPiWR) {
  EXPECT_GT(pulled(0.995, 0.05), -wall_break(0.05)) << "held below the pull-off force";
  EXPECT_LT(pulled(1.005, 0.05), -10 * wall_break(0.05)) << "pulled off above it";
  EXPECT_GT(pulled(0.995, 0.4), -wall_break(0.4));
  EXPECT_LT(pulled(1.005, 0.4), -10 * wall_break(0.4));
}

TEST(JkrLaw, PulledOffEveryWallKind) {
  // The same hold and release against a cylinder (the sphere inside it, its
  // surface through x = 0; R* = R, the wall's curvature neglected as with
  // every law) and a triangle mesh (a closed cube whose face x = 0 faces
  // the sphere, the sphere over the middle of a triangle): the law, its
  // reach and the wall's contact code together.
  std::ostringstream cyl, mesh;
  cyl.precision(17);
  mesh.precision(17);
  cyl << "{type: cylinder, base: [" << 20 * R << ", 0, " << -2 * R << "], axis: [0, 0, 1], radius: " << 20 * R
      << ", height: " << 4 * R << ", material: m}";
  mesh << "{type: mesh, file: " << GRAINS_SOURCE_DIR << "/tests/data/meshes/cube.off, scale: " << R
       << ", translate: [" << -R << ", 0, 0], material: m}";
  // (On the cylinder the sphere sits on the line y = 0 where its surface is
  // at x = 0; on the cube, off the diagonal edge of the face's two triangles.)
  for (const auto& [wall, y0] : {std::pair{cyl.str(), 0.0}, std::pair{mesh.str(), 0.3 * R}}) {
    SCOPED_TRACE(wall);
    EXPECT_GT(pulled(0.995, 0.05, "", 0.005, wall, y0), -wall_break(0.05)) << "held";
    EXPECT_LT(pulled(1.005, 0.05, "", 0.005, wall, y0), -10 * wall_break(0.05)) << "pulled off";
    EXPECT_GT(pulled(0.995, 0.05, "{skin: 1e-6}", 0.005, wall, y0), -wall_break(0.05)) << "tiny skin";
  }
}

TEST(JkrLaw, ContactInTensionIsHeldWithATinySkin) {
  // A skin of 1e-6 diameters (2 nm) is far below the pull-off separation
  // (~0.5 um): the wall's near list must reach it, or the sphere flies off.
  EXPECT_GT(pulled(0.995, 0.05, "{skin: 1e-6}"), -wall_break(0.05));
}

// Head-on collision of two equal spheres, no damping, relative speed v,
// surface energy g; returns the final relative speed (0 if they stuck) and
// whether they are in contact at the end. dt resolves d_c: v dt = d_c / 1000.
struct Outcome {
  double v_out;
  bool stuck;
};
Outcome collide(double v, double g, const std::string& neighbor = "") {
  const double w = 2 * g, Es = E / (2 * (1 - nu * nu));
  const auto [Fc, dc] = scales(w, Es, R / 2);
  (void)Fc;
  const double dt = 1e-3 * dc / v;
  const double gap = 0.01 * dc;
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [" << -10 * R << ", " << -2 * R << ", " << -2 * R << "], max: [" << 10 * R << ", " << 2 * R
    << ", " << 2 * R << "]}\n";
  y << "materials:\n  - {name: m, density: " << rho << ", youngs_modulus: " << E << ", poisson_ratio: " << nu
    << ", restitution: 1, surface_energy: " << g << "}\n";
  y << "contact: {model: jkr, tangential: none}\n";
  y << "particles:\n" << single("a", "m", sim::Vec3(-R - gap / 2, 0, 0), R, sim::Vec3(v / 2, 0, 0))
    << single("b", "m", sim::Vec3(R + gap / 2, 0, 0), R, sim::Vec3(-v / 2, 0, 0));
  if (!neighbor.empty()) y << "neighbor: " << neighbor << "\n";
  // Long enough for a few periods of the neck (sqrt(m*/k0) ~ 0.14 ms) or the
  // rebound to clear the break.
  y << "time: {dt: " << dt << ", end: " << 2e-3 << "}\n";
  auto s = from_yaml(y.str());
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
  const auto& p = sc.particles;
  const std::size_t a = index_of(p, 0), b = index_of(p, 1);
  const double overlap = 2 * R - (p.x[b] - p.x[a]).norm();
  const bool stuck = overlap > -JkrCurve::kBreak * dc;
  return {stuck ? 0.0 : p.v[b][0] - p.v[a][0], stuck};
}

// W: the work of Johnson's curve between touching (x_0 = (4/3)^(2/3)) and the
// break (x_f), lost in a collision without damping (in tension the force on
// the way out is not the zero force of the way in). Simpson's rule.
double lost_work(double Fc, double dc) {
  const double x0 = std::pow(4.0 / 3.0, 2.0 / 3.0);
  const int n = 20000;
  const double h = (x0 - x_f) / n;
  double sum = 0;
  for (int k = 0; k <= n; ++k) {
    const double x = x_f + k * h;
    const double f = -johnson_F(x) * (6 * x - 2 / std::sqrt(x));
    sum += f * (k == 0 || k == n ? 1 : k % 2 ? 4 : 2);
  }
  return Fc * dc * sum * h / 3;
}

TEST(JkrLaw, CriticalStickingVelocity) {
  const double g = 0.05, w = 2 * g, Es = E / (2 * (1 - nu * nu)), Rs = R / 2, ms = mass / 2;
  const auto [Fc, dc] = scales(w, Es, Rs);
  const double W = lost_work(Fc, dc);
  // The published closed form of this W (docs/dev/adhesion_sources.md 1.5).
  EXPECT_NEAR(W, 7.092 * std::pow(w, 5.0 / 3.0) * std::pow(Rs, 4.0 / 3.0) / std::pow(Es, 2.0 / 3.0), 1e-3 * W);
  const double vs = std::sqrt(2 * W / ms);
  // Thornton & Ning's form v_s = C (F_c^5 / (E*^2 R* m*^3))^(1/6) (with R*
  // to the first power, the dimensionally consistent reading), C from the
  // energy balance with the break at the vertical tangent: 1.035. Their
  // printed constant, 1.84, could not be checked against the paper's
  // definitions (docs/physics.md); the test holds the model to its energy.
  const double C = vs / std::pow(std::pow(Fc, 5) / (Es * Es * Rs * ms * ms * ms), 1.0 / 6.0);
  EXPECT_NEAR(C, 1.035, 0.001);
  const auto below = collide(0.97 * vs, g), above = collide(1.03 * vs, g);
  EXPECT_TRUE(below.stuck) << "3 % below v_s = " << vs << " m/s";
  EXPECT_FALSE(above.stuck) << "3 % above";
  EXPECT_GT(above.v_out, 0) << "moving apart";
}

TEST(JkrLaw, ElasticAdhesiveCollisionConservesEnergy) {
  // Above v_s the pair separates with v_out^2 = v_in^2 - v_s^2: the kinetic
  // energy less the work of the hysteresis loop, nothing else lost or gained.
  const double g = 0.05, w = 2 * g, Es = E / (2 * (1 - nu * nu)), Rs = R / 2, ms = mass / 2;
  const auto [Fc, dc] = scales(w, Es, Rs);
  const double vs = std::sqrt(2 * lost_work(Fc, dc) / ms);
  for (const double k : {1.2, 2.0, 5.0}) {
    const double v = k * vs;
    const auto o = collide(v, g);
    ASSERT_FALSE(o.stuck);
    const double expect = std::sqrt(v * v - vs * vs);
    EXPECT_NEAR(o.v_out, expect, 1e-3 * expect) << "at " << k << " v_s";
  }
  // The contact in tension is found with a skin far below d_f (the pair list's reach).
  const auto tiny = collide(2 * vs, g, "{skin: 1e-7}");
  EXPECT_NEAR(tiny.v_out, std::sqrt(3.0) * vs, 1e-3 * vs);
}

TEST(JkrLaw, RestitutionTendsToTheTargetWithoutAdhesion) {
  // At 1 m/s, far above v_s, the hysteresis costs nothing, but the adhesive
  // term still softens the contact by about 2 x^(-3/2) (x = a / a_c), which
  // changes what the damping does: the restitution reaches the requested
  // one (exactly Hertz's at w = 0, WithoutAdhesionIsHertzExactly) as w -> 0.
  for (const bool wall : {false, true}) {
    SCOPED_TRACE(wall ? "sphere-wall" : "sphere-sphere");
    const double e = impact(wall, E, nu, rho, R, 1.0, 0.6, 400, "{model: hertz, tangential: none}").restitution;
    double last = 1;
    for (const double w : {2e-3, 2e-4, 2e-5, 2e-6}) {
      std::ostringstream c;
      c << "{model: jkr, tangential: none, pairs: [{materials: [m, m], work_of_adhesion: " << w << "}]}";
      const double dev = std::abs(impact(wall, E, nu, rho, R, 1.0, 0.6, 400, c.str()).restitution - e);
      EXPECT_LT(dev, 0.5 * last) << "w = " << w;
      last = dev;
    }
    EXPECT_LT(last, 2e-4);
    EXPECT_NEAR(e, 0.6, 1e-3);
  }
}

}  // namespace
}  // namespace grains::test
