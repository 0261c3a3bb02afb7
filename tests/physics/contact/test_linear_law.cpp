// The linear spring-dashpot normal law (sim/laws/normal_linear.hpp) against
// the damped harmonic oscillator: a contact of effective mass m*, stiffness
// k_n and dashpot gamma_n lasts t_c = pi / sqrt(k_n/m* - (gamma_n/2m*)^2)
// and leaves with restitution e = exp(-gamma_n t_c / 2m*) (unclamped law,
// contact ends at zero overlap). Head-on impacts of two spheres (m* = m/2)
// and of a sphere on a plane (m* = m), run as cases through the real stages
// and the Verlet integrator, each within 0.5 % (measured: all within 0.12 %).
#include <gtest/gtest.h>

#include "tests/physics/contact/impact.hpp"

namespace grains::test {
namespace {

constexpr double E = 1e8, nu = 0.3, rho = 2500, R = 0.002;
// Steps per contact: the dashpot sees the mid-step velocity of velocity
// Verlet, a first-order error in dt (0.5 % of e = 0.3 at 400 steps).
constexpr int kSteps = 2000;
const double mass = rho * 4.0 / 3.0 * M_PI * R * R * R;

double analytic_tc(double k, double c, double ms) { return M_PI / std::sqrt(k / ms - (c / (2 * ms)) * (c / (2 * ms))); }

std::string linear(const std::string& keys) { return "{model: linear, tangential: none, linear: " + keys + "}"; }

TEST(LinearLaw, GivenStiffnessAndRestitution) {
  // gamma_n from e: the oscillator's restitution is e, whatever m* and k_n.
  const double k = 2e4;
  for (const bool wall : {false, true})
    for (const double e : {0.3, 0.7, 1.0}) {
      const double ms = wall ? mass : mass / 2;
      const double le = std::log(e), c = 2 * std::sqrt(ms * k) * -le / std::sqrt(M_PI * M_PI + le * le);
      const double tc = analytic_tc(k, c, ms);
      const auto r = impact(wall, E, nu, rho, R, 0.5, e, kSteps, linear("{stiffness: 2e4}"), tc);
      SCOPED_TRACE(std::string(wall ? "sphere-wall" : "sphere-sphere") + " e=" + std::to_string(e));
      EXPECT_NEAR(r.restitution / e, 1.0, 0.005);
      EXPECT_NEAR(r.contact_time / tc, 1.0, 0.005);
      // Peak overlap of the undamped oscillator, v sqrt(m*/k), as a check of k_n itself.
      if (e == 1.0) {
        EXPECT_NEAR(r.max_overlap / ((wall ? 0.5 : 1.0) * std::sqrt(ms / k)), 1.0, 0.005);
      }
    }
}

TEST(LinearLaw, GivenStiffnessAndDamping) {
  const double k = 2e4, c = 0.02;
  for (const bool wall : {false, true}) {
    const double ms = wall ? mass : mass / 2;
    const double tc = analytic_tc(k, c, ms);
    const double e = std::exp(-c * tc / (2 * ms));
    const auto r = impact(wall, E, nu, rho, R, 0.5, 0.9, kSteps, linear("{stiffness: 2e4, damping: 0.02}"), tc);
    SCOPED_TRACE(wall ? "sphere-wall" : "sphere-sphere");
    EXPECT_NEAR(r.restitution / e, 1.0, 0.005);
    EXPECT_NEAR(r.contact_time / tc, 1.0, 0.005);
  }
}

TEST(LinearLaw, GivenStiffnessAndDampingRate) {
  // LAMMPS's gran/hooke: gamma_n = m* x rate, so e = exp(-rate t_c / 2) with
  // t_c = pi / sqrt(k/m* - rate^2/4): the same e on a wall (m* = m) and
  // between two spheres (m* = m/2) only when k/m* is large.
  const double k = 2e4, rate = 4000;
  for (const bool wall : {false, true}) {
    const double ms = wall ? mass : mass / 2;
    const double tc = M_PI / std::sqrt(k / ms - 0.25 * rate * rate);
    const double e = std::exp(-0.5 * rate * tc);
    const auto r = impact(wall, E, nu, rho, R, 0.5, 0.9, kSteps, linear("{stiffness: 2e4, damping_rate: 4000}"), tc);
    SCOPED_TRACE(wall ? "sphere-wall" : "sphere-sphere");
    EXPECT_NEAR(r.restitution / e, 1.0, 0.005);
    EXPECT_NEAR(r.contact_time / tc, 1.0, 0.005);
  }
}

TEST(LinearLaw, GivenContactTime) {
  // k_n and gamma_n per contact from t_c and e: sphere-sphere and sphere-wall
  // (m* twice as large) last the same time.
  const double tc = 3e-4, e = 0.5;
  for (const bool wall : {false, true}) {
    const auto r = impact(wall, E, nu, rho, R, 0.5, e, kSteps, linear("{contact_time: 3e-4}"), tc);
    SCOPED_TRACE(wall ? "sphere-wall" : "sphere-sphere");
    EXPECT_NEAR(r.restitution / e, 1.0, 0.005);
    EXPECT_NEAR(r.contact_time / tc, 1.0, 0.005);
  }
}

TEST(LinearLaw, CharacteristicVelocityGivesHertzPeakOverlap) {
  // LIGGGHTS's hooke: at the characteristic velocity the peak overlap of
  // the elastic linear contact equals Hertz's.
  const double v = 0.5;
  for (const bool wall : {false, true}) {
    const double ms = wall ? mass : mass / 2, Rs = wall ? R : R / 2, vrel = wall ? v : 2 * v;
    const double Es = E / (2 * (1 - nu * nu));  // the wall is of the same material (as in the pair table)
    const double dmax = std::pow(15 * ms * vrel * vrel / (16 * Es * std::sqrt(Rs)), 0.4);
    const double k = ms * vrel * vrel / (dmax * dmax);
    const auto r = impact(wall, E, nu, rho, R, v, 1.0, 400,
                          linear("{characteristic_velocity: " + std::to_string(vrel) + "}"), analytic_tc(k, 0, ms));
    SCOPED_TRACE(wall ? "sphere-wall" : "sphere-sphere");
    EXPECT_NEAR(r.max_overlap / dmax, 1.0, 0.005);
    EXPECT_NEAR(r.restitution, 1.0, 0.005);
  }
}

TEST(LinearLaw, LimitForceKeepsTheContactFromPulling) {
  // Clamped at zero the unloading ends earlier with less energy lost.
  const double k = 2e4, ms = mass / 2, e = 0.3;
  const double le = std::log(e), c = 2 * std::sqrt(ms * k) * -le / std::sqrt(M_PI * M_PI + le * le);
  const double tc = analytic_tc(k, c, ms);
  const auto r = impact(false, E, nu, rho, R, 0.5, e, kSteps, linear("{stiffness: 2e4, limit_force: true}"), tc);
  EXPECT_GT(r.restitution, e * 1.05);
  EXPECT_LT(r.restitution, 1.0);
}

TEST(LinearLaw, PipelineNamesTheLawAndItsTangentialSpring) {
  std::ostringstream y;
  y << "domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}\nmaterials:\n"
    << material("m", rho, E, nu, 0.5, 0.4) << "contact: {model: linear, linear: {stiffness: 1e4}}\nparticles:\n"
    << single("a", "m", sim::Vec3(0, 0, 0), R, sim::Vec3::Zero()) << "time: {dt: 1e-6, end: 1e-5}\n";
  auto s = from_yaml(y.str());
  const auto names = s.pipeline.stage_names();
  bool found = false;
  for (const auto& n : names)
    found = found || n == "force: force.pair_contacts<linear+tangential:linear+rolling:none+cohesion:none>";
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace grains::test
