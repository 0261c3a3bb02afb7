// radius_growth (sim/integrate/radius_growth.hpp): free growth at the given
// rate with the density kept, the cap at max_scale, no touching pair missing
// from the neighbour list while radii grow (walls and a periodic box), the
// servo holding the overlap per particle at its target, and set-up errors.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <sstream>

#include "sim/integrate/radius_growth.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

sim::RadiusGrowth* growth_stage(io::Simulation& s) {
  for (const auto& st : s.pipeline.stages())
    if (auto* g = dynamic_cast<sim::RadiusGrowth*>(st.get())) return g;
  return nullptr;
}

// n spheres of radius r0 in a cube of side L (walls, or periodic), growing.
std::string box_case(int n, double r0, double L, double rate, double target, double end, bool periodic,
                     double max_scale = 2, double skin = 0.1) {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [0, 0, 0], max: [" << L << ", " << L << ", " << L << "]"
    << (periodic ? ", periodic: [true, true, true]" : "") << "}\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.1, 0.0)
    << "particles:\n  - {material: m, radius: " << r0 << ", count: " << n
    << ", placement: {type: random_fill, seed: 5, region: {min: [" << r0 << ", " << r0 << ", " << r0 << "], max: ["
    << L - r0 << ", " << L - r0 << ", " << L - r0 << "]}}}\n";
  if (!periodic) {
    y << "walls:\n";
    const char* axes[3] = {"[1, 0, 0]", "[0, 1, 0]", "[0, 0, 1]"};
    const char* back[3] = {"[-1, 0, 0]", "[0, -1, 0]", "[0, 0, -1]"};
    for (int d = 0; d < 3; ++d) {
      y << "  - {type: plane, point: [0, 0, 0], normal: " << axes[d] << ", material: m}\n";
      y << "  - {type: plane, point: [" << L << ", " << L << ", " << L << "], normal: " << back[d] << ", material: m}\n";
    }
  }
  y << "radius_growth: {rate: " << rate << ", target_overlap: " << target << ", max_scale: " << max_scale << "}\n"
    << "neighbor: {skin: " << skin << "}\n"
    << "time: {dt_rayleigh: 0.2, end: " << end << "}\n";
  return y.str();
}

TEST(RadiusGrowth, FreeGrowthAtTheRateWithTheDensityKept) {
  // Three particles far apart never touch: r(t) = r0 exp(rate t), m ~ r^3.
  auto s = from_yaml(box_case(3, 0.0002, 0.01, 5.0, 1e-3, 0.02, false));
  ASSERT_NE(growth_stage(s), nullptr);
  const double m0 = s.scene.particles.mass[0];
  s.pipeline.initialize(s.scene);
  while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
  const auto& p = s.scene.particles;
  const double scale = std::exp(5.0 * s.scene.clock.time);
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    EXPECT_NEAR(p.radius[i] / 0.0002, scale, 1e-9 * scale);
    EXPECT_NEAR(p.mass[i] / m0, scale * scale * scale, 1e-8);
    EXPECT_NEAR(p.inv_mass[i] * p.mass[i], 1.0, 1e-12);
  }
  EXPECT_FALSE(growth_stage(s)->capped());
}

TEST(RadiusGrowth, StopsAtMaxScale) {
  auto s = from_yaml(box_case(3, 0.0002, 0.01, 20.0, 1e-3, 0.05, false, 1.5));
  s.pipeline.initialize(s.scene);
  while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
  for (std::size_t i = 0; i < s.scene.particles.n_owned(); ++i)
    EXPECT_NEAR(s.scene.particles.radius[i], 1.5 * 0.0002, 1e-12);
  EXPECT_TRUE(growth_stage(s)->capped());
}

// Every pair that touches (brute force, minimum image in a periodic box) is
// in the neighbour list, with the contact distance of the current radii.
void expect_list_complete(const io::Simulation& s, double L, bool periodic) {
  const auto& p = s.scene.particles;
  const auto& nl = s.scene.neighbors;
  std::set<std::pair<std::int64_t, std::int64_t>> listed;
  const std::size_t rows = nl.row_start.size() - 1;
  for (std::size_t i = 0; i < rows; ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const auto j = nl.partner[k];
      const double rs = p.radius[i] + p.radius[j];
      ASSERT_EQ(nl.contact_distance(p, i, j), rs);
      listed.emplace(std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j]));
    }
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    for (std::size_t j = i + 1; j < p.n_owned(); ++j) {
      sim::Vec3 d = p.x[i] - p.x[j];
      if (periodic)
        for (int c = 0; c < 3; ++c) d[c] -= L * std::round(d[c] / L);
      const double rs = p.radius[i] + p.radius[j];
      if (d.squaredNorm() < rs * rs) {
        ASSERT_TRUE(listed.count({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])}))
            << "touching pair " << p.id[i] << "-" << p.id[j] << " missing at step " << s.scene.clock.step;
      }
    }
}

void grow_and_check(bool periodic) {
  // 300 spheres from a fill fraction of about 0.13 grown fast (rate 20/s)
  // with a small skin (0.02 d) so that the list is rebuilt often by growth.
  const double L = 0.006, r0 = 0.0003;
  auto s = from_yaml(box_case(300, r0, L, 20.0, 3e-3, 0.04, periodic, 2.0, 0.02));
  s.pipeline.initialize(s.scene);
  const long builds0 = s.scene.neighbors.stats().builds;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    if (s.scene.clock.step % 25 == 0) expect_list_complete(s, L, periodic);
    if (testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(s.scene.particles.radius[0], 1.5 * r0);  // it did grow (0.13 -> 0.44 at scale 1.5)
  EXPECT_GT(s.scene.neighbors.stats().builds - builds0, 20);
}

TEST(RadiusGrowth, TwoSpheresAtRestMeetByGrowthAndPushApart) {
  // Nothing moves but the radii: only the growth term of the rebuild trigger
  // brings the pair into the list before they touch. Without it they would
  // pass into each other unopposed.
  const double r0 = 0.0005;
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.01, -0.01, -0.01], max: [0.01, 0.01, 0.01]}\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0.0) << "particles:\n"
    << single("a", "m", sim::Vec3(-0.0008, 0, 0), r0, sim::Vec3::Zero())
    << single("b", "m", sim::Vec3(0.0008, 0, 0), r0, sim::Vec3::Zero())
    << "radius_growth: {rate: 20, target_overlap: 0.01, max_scale: 2}\nneighbor: {skin: 0.05}\n"
    << "time: {dt_rayleigh: 0.2, end: 0.03}\n";
  auto s = from_yaml(y.str());
  s.pipeline.initialize(s.scene);
  double worst = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    const auto& p = s.scene.particles;
    worst = std::max(worst, (p.radius[0] + p.radius[1] - (p.x[0] - p.x[1]).norm()) / p.radius[0]);
  }
  const auto& p = s.scene.particles;
  EXPECT_GT(p.radius[0], 1.7 * r0);  // 0.0016 apart: they met at 1.6 r0
  EXPECT_GT((p.x[0] - p.x[1]).norm(), 0.0017);  // pushed apart
  EXPECT_LT(worst, 0.05);                       // never deep into each other
}

TEST(RadiusGrowth, NoTouchingPairIsMissedBetweenRebuilds) { grow_and_check(false); }
TEST(RadiusGrowth, NoTouchingPairIsMissedInAPeriodicBox) { grow_and_check(true); }

TEST(RadiusGrowth, ServoHoldsTheOverlapPerParticleAtTheTarget) {
  // 400 spheres in a periodic box compressed past jamming to a target
  // overlap per particle of 2e-3: the measured o settles within 20 % of it
  // and the packing is dense (above random loose packing).
  const double L = 0.006, r0 = 0.00028;  // fill fraction 0.17
  auto s = from_yaml(box_case(400, r0, L, 5.0, 2e-3, 0.25, true, 2.0));
  s.pipeline.initialize(s.scene);
  while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
  const double o = sim::RadiusGrowth::overlap_per_particle(s.scene);
  EXPECT_NEAR(o / 2e-3, 1.0, 0.2);
  double v = 0;
  for (std::size_t i = 0; i < s.scene.particles.n_owned(); ++i) v += std::pow(s.scene.particles.radius[i], 3);
  const double phi = 4.0 / 3.0 * M_PI * v / (L * L * L);
  EXPECT_GT(phi, 0.60);
  EXPECT_LT(phi, 0.68);
  EXPECT_FALSE(growth_stage(s)->capped());
}

TEST(RadiusGrowth, PhasesRunInTurnAndRadiiStayFixedAfterwards) {
  // Free particles: 5/s until 0.01 s, then 0 (held), then 10/s until 0.03 s,
  // then fixed to the end: r = r0 exp(5 x 0.01 + 10 x 0.01).
  std::string y = box_case(3, 0.0002, 0.01, 5.0, 1e-3, 0.04, false);
  y.replace(y.find("radius_growth: {rate: 5"), y.find("\n", y.find("radius_growth:")) - y.find("radius_growth: {rate: 5"),
            "radius_growth: {phases: [{rate: 5, target_overlap: 1e-3, until: 0.01}, {rate: 0, target_overlap: 1e-3, "
            "until: 0.02}, {rate: 10, target_overlap: 1e-3, until: 0.03}]}");
  auto s = from_yaml(y);
  s.pipeline.initialize(s.scene);
  double r_mid = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    if (r_mid == 0 && s.scene.clock.time >= 0.015) r_mid = s.scene.particles.radius[0];
  }
  const double dt = s.scene.clock.dt;
  EXPECT_NEAR(r_mid / 0.0002, std::exp(0.05), 5 * dt * std::exp(0.05));  // one step of either phase boundary
  EXPECT_NEAR(s.scene.particles.radius[0] / 0.0002, std::exp(0.15), 20 * dt * std::exp(0.15));
  // Case errors: phases with rate/target, and out of order.
  const auto err = [&](const std::string& g) {
    std::string t = y;
    t.replace(t.find("radius_growth:"), t.find("\n", t.find("radius_growth:")) - t.find("radius_growth:"), g);
    try {
      (void)from_yaml(t);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(err("radius_growth: {rate: 1, phases: [{rate: 1, target_overlap: 1e-3, until: 0.1}]}")
                .find("either rate and target_overlap, or phases"),
            std::string::npos);
  EXPECT_NE(err("radius_growth: {phases: [{rate: 1, target_overlap: 1e-3, until: 0.1}, {rate: 1, target_overlap: "
                "1e-3, until: 0.05}]}")
                .find("phases must be in time order"),
            std::string::npos);
  EXPECT_NE(err("radius_growth: {max_scale: 1.5}").find("missing rate and target_overlap"), std::string::npos);
}

TEST(RadiusGrowth, RefusedForEllipsoids) {
  std::string y = box_case(10, 0.0003, 0.006, 1.0, 1e-3, 0.001, false);
  y.replace(y.find(", count: 10"), 11, ", count: 10, shape: {type: ellipsoid, aspect_ratio: 1.5}");
  try {
    (void)from_yaml(y);
    FAIL() << "accepted";
  } catch (const sim::SetupError& e) {
    EXPECT_NE(std::string(e.what()).find("radius_growth grows spheres only"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("test.yaml:"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace grains::test
