// Periodic boundaries (serial: a rank is its own neighbour across a periodic
// face): a particle leaving through a face comes back through the opposite
// one, contacts act across the faces with the same physics as inside, and
// a periodic box too small for its particles is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "sim/parallel/exchange.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

// Two spheres in a periodic box along x, approaching each other across the
// x faces (or, for the reference, in the middle of the box).
std::string two_spheres(bool across, double e) {
  std::ostringstream o;
  o.precision(17);
  const double r = 0.001, L = 0.01;
  // Across: a near x = 0 moving left, b near x = L moving right (gap 0.4 mm
  // through the face); inside: a left of b, moving towards it.
  const double xa = across ? 0.0012 : 0.0038, xb = across ? L - 0.0012 : 0.0062;
  const double va = across ? -0.5 : 0.5;
  o << "domain: {min: [0, 0, 0], max: [" << L << ", 0.006, 0.006], periodic: [true, false, false]}\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, e, 0) << "particles:\n"
    << single("a", "m", sim::Vec3(xa, 0.003, 0.003), r, sim::Vec3(va, 0, 0))
    << single("b", "m", sim::Vec3(xb, 0.003, 0.003), r, sim::Vec3(-va, 0, 0))
    << "time: {dt_rayleigh: 0.01, end: 0.003}\n";  // ~230 steps per contact
  return o.str();
}

double run_and_relative_speed(const std::string& yaml, std::int64_t& lost) {
  auto s = from_yaml(yaml);
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
  lost = sc.lost_particles;
  const auto& p = sc.particles;
  const auto a = index_of(p, 0), b = index_of(p, 1);
  EXPECT_EQ(p.n_owned(), 2u);
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    EXPECT_GE(p.x[i].x(), sc.domain.lo.x() - 0.001);  // wrapped back into the box (up to a skin)
    EXPECT_LE(p.x[i].x(), sc.domain.hi.x() + 0.001);
  }
  return (p.v[a] - p.v[b]).x();
}

TEST(Periodic, ContactAcrossTheFaceHasTheSameRestitution) {
  // Single-particle sets are placed as lattices: the helper puts each where asked.
  for (double e : {0.3, 0.5, 0.9}) {
    std::int64_t lost_a = -1, lost_b = -1;
    // Either way |v_rel| after = e |v_rel| before (1 m/s).
    const double across = run_and_relative_speed(two_spheres(true, e), lost_a);
    const double inside = run_and_relative_speed(two_spheres(false, e), lost_b);
    EXPECT_EQ(lost_a, 0);
    EXPECT_EQ(lost_b, 0);
    EXPECT_NEAR(std::abs(across), e * 1.0, 0.01 * e) << "e = " << e;
    EXPECT_NEAR(std::abs(across), std::abs(inside), 1e-6) << "e = " << e;
  }
}

TEST(Periodic, ParticleLeavingComesBack) {
  std::ostringstream o;
  o << "domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01], periodic: true}\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0) << "particles:\n"
    << single("a", "m", sim::Vec3(0.005, 0.005, 0.005), 0.001, sim::Vec3(1, 0.7, -0.4))
    << "time: {dt_rayleigh: 0.2, end: 0.05}\n";
  auto s = from_yaml(o.str());
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  while (sc.clock.step < sc.clock.n_steps) s.pipeline.step(sc);
  EXPECT_EQ(sc.lost_particles, 0);
  ASSERT_EQ(sc.particles.n_owned(), 1u);
  // Free flight: 5 box lengths in x; the unwrapped position is x0 + v t.
  const double t = sc.clock.time;
  for (int d = 0; d < 3; ++d) {
    const double v = d == 0 ? 1 : d == 1 ? 0.7 : -0.4;
    double expect = std::fmod(0.005 + v * t, 0.01);
    if (expect < 0) expect += 0.01;
    double got = sc.particles.x[0][d];
    // Between rebuilds the particle may be up to half a skin outside the box.
    double diff = std::fmod(std::abs(got - expect), 0.01);
    diff = std::min(diff, 0.01 - diff);
    EXPECT_LT(diff, 1e-9) << "axis " << d;
  }
}

TEST(Periodic, InitialOverlapThroughAFaceIsRefused) {
  std::ostringstream o;
  o << "domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01], periodic: [true, false, false]}\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0) << "particles:\n"
    << single("a", "m", sim::Vec3(0.0004, 0.005, 0.005), 0.001, sim::Vec3(0, 0, 0))
    << single("b", "m", sim::Vec3(0.0088, 0.005, 0.005), 0.001, sim::Vec3(0, 0, 0))
    << "time: {dt_rayleigh: 0.2, end: 0.001}\n";
  try {
    from_yaml(o.str());
    FAIL() << "spheres overlapping through a periodic face must be refused";
  } catch (const sim::SetupError& e) {
    EXPECT_NE(std::string(e.what()).find("overlap by 0.0004 m"), std::string::npos) << e.what();
  }
}

TEST(Periodic, BoxTooSmallIsRefused) {
  std::ostringstream o;
  o << "domain: {min: [0, 0, 0], max: [0.003, 0.01, 0.01], periodic: [true, false, false]}\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0) << "particles:\n"
    << single("a", "m", sim::Vec3(0.0015, 0.005, 0.005), 0.001, sim::Vec3(0, 0, 0))
    << "time: {dt_rayleigh: 0.2, end: 0.001}\n";
  try {
    from_yaml(o.str());
    FAIL() << "a periodic box under twice the cut-off must be refused";
  } catch (const sim::SetupError& e) {
    EXPECT_NE(std::string(e.what()).find("periodic box is too small along x"), std::string::npos) << e.what();
  }
}

// A wide size distribution: each grain's images reach r + r_max + skin from
// the face, not 2 r_max + skin (the farthest a partner of it lies), so a
// small grain has fewer of them; the list still holds every pair, through
// the faces included, exactly as brute force over the periodic images.
TEST(Periodic, SmallGrainsImagesReachOnlyAsFarAsTheirPairs) {
  const double L = 0.015;
  std::ostringstream o;
  o << "domain: {min: [0, 0, 0], max: [" << L << ", " << L << ", 0.005], periodic: [true, true, false]}\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0) << "particles:\n"
    << "  - {material: m, radius: 0.002, count: 6, placement: {type: random_fill, region: {min: [0, 0, 0], max: ["
    << L << ", " << L << ", 0.005]}}}\n"
    << "  - {material: m, radius: 0.0002, count: 2500, placement: {type: random_fill, region: {min: [0, 0, 0], max: ["
    << L << ", " << L << ", 0.005]}}}\n"
    << "neighbor: {skin_per_grain: false}\n"
    << "time: {dt_rayleigh: 0.2, end: 0.001}\n";
  auto s = from_yaml(o.str());
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  const auto& p = sc.particles;
  const std::size_t n = p.n_owned();
  ASSERT_EQ(n, 2506u);
  ASSERT_TRUE(sc.exchange);
  const double cut = sc.exchange->cutoff(), skin = sc.neighbors.skin(), R = 0.002;
  EXPECT_NEAR(cut, 2 * R + skin, 1e-15);
  // Images per grain: along x and y, each face within its reach, and the corners.
  auto images = [&](std::size_t i, double c) {
    int a[2];
    for (int d = 0; d < 2; ++d) a[d] = (p.x[i][d] < c) + (p.x[i][d] >= L - c);
    return static_cast<std::size_t>((1 + a[0]) * (1 + a[1]) - 1);
  };
  std::size_t own_reach = 0, whole_cut = 0;
  for (std::size_t i = 0; i < n; ++i) own_reach += images(i, cut - R + p.radius[i]), whole_cut += images(i, cut);
  EXPECT_EQ(sc.exchange->stats().images_built, own_reach);
  EXPECT_LT(p.n_ghost(), own_reach);  // those in no list entry dropped
  EXPECT_LT(static_cast<double>(own_reach), 0.7 * static_cast<double>(whole_cut));
  // The list's entries as (owned or row id, other id, image shift) against brute force.
  std::map<std::int64_t, std::size_t> at;
  for (std::size_t i = 0; i < n; ++i) at[p.id[i]] = i;
  auto shift = [&](std::size_t k, int d) { return static_cast<int>(std::lround((p.x[k][d] - p.x[at[p.id[k]]][d]) / L)); };
  std::multiset<std::tuple<std::int64_t, std::int64_t, int, int>> got, want;
  const auto& nl = sc.neighbors;
  for (std::size_t r = 0; r + 1 < nl.row_start.size(); ++r)
    for (auto k = nl.row_start[r]; k < nl.row_start[r + 1]; ++k) {
      std::size_t a = r, b = nl.partner[k];
      if (a >= n) std::swap(a, b);  // the owned one first
      ASSERT_LT(a, n) << "a pair of two images";
      if (b < n && p.id[a] > p.id[b]) std::swap(a, b);
      got.insert({p.id[a], p.id[b], shift(b, 0), shift(b, 1)});
    }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      for (int sx = -1; sx <= 1; ++sx)
        for (int sy = -1; sy <= 1; ++sy) {
          const bool image = sx != 0 || sy != 0;
          if (!image && p.id[i] >= p.id[j]) continue;  // a pair inside the box: once
          const sim::Vec3 xj = p.x[j] + sim::Vec3(sx * L, sy * L, 0);
          if ((p.x[i] - xj).norm() < p.radius[i] + p.radius[j] + skin) want.insert({p.id[i], p.id[j], sx, sy});
        }
  EXPECT_EQ(got, want);
  std::size_t through = 0, small_through = 0;  // pairs through the faces, of two small grains
  for (const auto& [a, b, sx, sy] : want)
    if (sx != 0 || sy != 0) ++through, small_through += p.radius[at[a]] < R && p.radius[at[b]] < R;
  EXPECT_GT(through, 30u) << want.size();
  EXPECT_GT(small_through, 10u) << want.size();
}

// Steps a periodic scene (box of side L along x and y) and checks after each
// step that every image is at its grain's position, shifted, and is in a
// list entry or is the image another image is made from; counts the images
// built and kept.
struct ImageCheck {
  std::size_t steps = 0, built = 0, kept = 0, listed = 0;
};
ImageCheck step_and_check_images(const std::string& yaml, double L, std::size_t steps) {
  ImageCheck out;
  auto s = from_yaml(yaml);
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  const auto& p = sc.particles;
  const auto& nl = sc.neighbors;
  while (sc.clock.step < sc.clock.n_steps && out.steps < steps) {
    s.pipeline.step(sc);
    ++out.steps;
    const std::size_t n = p.n_owned();
    std::map<std::int64_t, std::size_t> at;
    for (std::size_t i = 0; i < n; ++i) at[p.id[i]] = i;
    std::vector<char> listed(p.size(), 0);
    for (std::size_t r = 0; r + 1 < nl.row_start.size(); ++r)
      for (auto k = nl.row_start[r]; k < nl.row_start[r + 1]; ++k) listed[r] = listed[nl.partner[k]] = 1;
    out.built += sc.exchange->stats().images_built;
    out.kept += p.n_ghost();
    for (std::size_t g = n; g < p.size(); ++g) {
      const std::size_t i = at.at(p.id[g]);
      bool same = true;  // positions (the kick after the forces moved on the grains' velocities)
      for (int d = 0; d < 3; ++d) {
        const double dx = p.x[g][d] - p.x[i][d];
        const double shifted = std::abs(dx) > 0.5 * L ? p.x[i][d] + std::copysign(L, dx) : p.x[i][d];
        same = same && p.x[g][d] == shifted;
      }
      EXPECT_TRUE(same) << "step " << sc.clock.step << ": the image of grain " << p.id[g] << " is stale";
      if (!same) return out;
      out.listed += listed[g];
    }
  }
  return out;
}

// After each build the images no list entry uses are dropped (unless an
// image in one is made from them): every image left is fresh after each
// step, and most small grains' images are gone.
TEST(Periodic, ImagesInNoListEntryAreDropped) {
  const double L = 0.015;
  std::ostringstream o;
  o << "domain: {min: [0, 0, 0], max: [" << L << ", " << L << ", 0.005], periodic: [true, true, false]}\n"
    << "gravity: [3, 2, 0]\n"  // along the periodic axes: every grain moves and wraps
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0) << "particles:\n"
    << "  - {material: m, radius: 0.002, count: 6, placement: {type: random_fill, region: {min: [0, 0, 0], max: ["
    << L << ", " << L << ", 0.005]}}}\n"
    << "  - {material: m, radius: 0.0002, count: 2500, placement: {type: random_fill, region: {min: [0, 0, 0], max: ["
    << L << ", " << L << ", 0.005]}}}\n"
    << "time: {dt_rayleigh: 0.2, end: 0.01}\n";
  const auto c = step_and_check_images(o.str(), L, 40);
  EXPECT_EQ(c.steps, 40u);
  EXPECT_GT(c.listed, 40u * 30u);
  EXPECT_LT(2 * c.kept, c.built) << "most images are in no list entry";
}

// Two grains in opposite corners of the box, a pair only through the corner:
// the corner image (made from the image across x) is in the list, the image
// across x is not, and is kept (and refreshed) all the same; the image
// across y goes.
TEST(Periodic, ImageACornerImageIsMadeFromIsKept) {
  const double L = 0.01, r = 0.001, a = 0.7072 * r * 1.02;  // 2 sqrt(2) a just beyond 2 r
  std::ostringstream o;
  o.precision(17);
  o << "domain: {min: [0, 0, 0], max: [" << L << ", " << L << ", 0.004], periodic: [true, true, false]}\n"
    << "gravity: [3, 2, 0]\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0) << "particles:\n"
    << single("a", "m", sim::Vec3(a, a, 0.002), r, sim::Vec3(0, 0, 0))
    << single("b", "m", sim::Vec3(L - a, L - a, 0.002), r, sim::Vec3(0, 0, 0))
    << "neighbor: {skin: 0.1}\n"
    << "time: {dt_rayleigh: 0.2, end: 0.01}\n";
  const auto c = step_and_check_images(o.str(), L, 30);
  EXPECT_EQ(c.steps, 30u);
  EXPECT_EQ(c.built, 30u * 6u);   // each grain's images across x, across y and through the corner
  EXPECT_EQ(c.kept, 30u * 4u);    // not those across y
  EXPECT_EQ(c.listed, 30u * 2u);  // the corner images
}

TEST(Periodic, CaseKeyErrors) {
  const std::string base = "materials:\n" + material("m", 2500, 1e7, 0.3, 0.5, 0) + "particles:\n" +
                           single("a", "m", sim::Vec3(0.005, 0.005, 0.005), 0.001, sim::Vec3(0, 0, 0)) +
                           "time: {dt_rayleigh: 0.2, end: 0.001}\n";
  try {
    from_yaml("domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01], periodic: [true, false]}\n" + base);
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("test.yaml:1:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("periodic must be true, false or a list of 3 booleans"), std::string::npos)
        << e.what();
  }
  try {
    from_yaml("domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}\nparallel: {decomposition: [2, 0, 1]}\n" + base);
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("decomposition must be 3 positive integers"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace grains::test
