// The Verlet list holds every pair within r_i + r_j + skin exactly once,
// the displacement trigger fires before a pair can be missed, and contact
// history follows its pair through re-sorting, removals and rebuilds.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>

#include "sim/neighbor/neighbor_list.hpp"

namespace grains::sim {
namespace {

ParticleStore random_store(std::mt19937_64& rng, std::size_t n, double L) {
  ParticleStore p;
  p.configure(FieldSet{}, 0);
  std::uniform_real_distribution<double> u(0, L), r(0.02, 0.05);
  for (std::size_t i = 0; i < n; ++i)
    p.add(static_cast<std::int64_t>(i), Vec3(u(rng), u(rng), u(rng)), Vec3::Zero(), r(rng), 1.0, 0);
  return p;
}

std::set<std::pair<std::int64_t, std::int64_t>> list_pairs(const NeighborList& nl, const ParticleStore& p) {
  std::set<std::pair<std::int64_t, std::int64_t>> s;
  for (std::size_t i = 0; i + 1 < nl.row_start.size(); ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const auto a = p.id[i], b = p.id[nl.partner[k]];
      EXPECT_LT(a, b) << "a pair lives in the row of the smaller id";
      EXPECT_TRUE(s.insert({a, b}).second) << "pair listed twice";
    }
  return s;
}

// The pairs a list must hold, by brute force, with the rules of the build:
// the pair skin (one skin, or f (ri + rj) up to it), no ghost-ghost pair, no
// pair of a grain with its own image, none within one clump.
std::set<std::pair<std::int64_t, std::int64_t>> brute_pairs(const ParticleStore& p, double skin, double f) {
  std::set<std::pair<std::int64_t, std::int64_t>> s;
  const std::size_t n = p.size(), own = p.n_owned();
  const bool bodies = p.fields().has(Field::Body);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if ((i >= own && j >= own) || p.id[i] == p.id[j]) continue;
      if (bodies && p.body[i] >= 0 && p.body[i] == p.body[j]) continue;
      const double sk = f > 0 ? std::min(f * (p.radius[i] + p.radius[j]), skin) : skin;
      const double c = p.radius[i] + p.radius[j] + sk;
      if ((p.x[i] - p.x[j]).squaredNorm() < c * c) s.insert({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])});
    }
  return s;
}

TEST(NeighborList, MatchesBruteForce) {
  std::mt19937_64 rng(1);
  for (const bool sort : {false, true}) {
    auto p = random_store(rng, 1500, 1.0);
    NeighborList nl;
    const double skin = 0.01;
    nl.configure(0, skin);
    Walls w;
    nl.build(p, w, Vec3(0, 0, 0), Vec3(1, 1, 1), 0, sort);
    const auto brute = brute_pairs(p, skin, 0.0);
    EXPECT_EQ(list_pairs(nl, p), brute);
    EXPECT_GT(brute.size(), 100u);
  }
}

// The cells of a build are walked as runs of neighbouring cells in x: boxes
// one or two cells thick in some direction, and one cell in all, keep every
// pair too (the runs clipped at the box's faces), with one size and with
// sizes over a ratio of 9 (searched by size class).
TEST(NeighborList, ThinBoxesMatchBruteForce) {
  std::mt19937_64 rng(7);
  const Vec3 boxes[] = {{1.0, 1.0, 0.1}, {0.1, 1.0, 1.0}, {1.0, 0.15, 0.25}, {0.1, 0.1, 0.1}, {2.0, 0.2, 0.2}};
  for (const bool wide : {false, true})
    for (const Vec3& box : boxes) {
      ParticleStore p;
      p.configure(FieldSet{}, 0);
      std::uniform_real_distribution<double> u(0, 1), r(wide ? 0.005 : 0.02, 0.045);
      const std::size_t n = static_cast<std::size_t>(3000 * box.prod()) + 20;
      for (std::size_t i = 0; i < n; ++i)
        p.add(static_cast<std::int64_t>(n - i), Vec3(u(rng) * box[0], u(rng) * box[1], u(rng) * box[2]), Vec3::Zero(),
              r(rng), 1.0, 0);
      NeighborList nl;
      const double skin = 0.015;
      nl.configure(0, skin);
      Walls w;
      nl.build(p, w, Vec3(0, 0, 0), box, 0, true);
      const auto brute = brute_pairs(p, skin, 0.0);
      EXPECT_EQ(list_pairs(nl, p), brute) << "box " << box.transpose() << (wide ? ", wide sizes" : "");
      EXPECT_GT(brute.size(), 10u);
    }
}

TEST(NeighborList, TriggerFiresBeforeAPairIsMissed) {
  std::mt19937_64 rng(2);
  auto p = random_store(rng, 800, 1.0);
  NeighborList nl;
  const double skin = 0.02;
  nl.configure(0, skin);
  Walls w;
  nl.build(p, w, Vec3(0, 0, 0), Vec3(1, 1, 1), 0, true);
  std::normal_distribution<double> step(0, 0.001);
  for (int it = 0; it < 400; ++it) {
    for (std::size_t i = 0; i < p.size(); ++i) p.x[i] += Vec3(step(rng), step(rng), step(rng));
    if (nl.needs_rebuild(p, w, 0)) nl.build(p, w, Vec3(-1, -1, -1), Vec3(2, 2, 2), 0, true);
    // Every touching pair must be in the list.
    const auto listed = list_pairs(nl, p);
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t j = i + 1; j < p.size(); ++j) {
        const double c = p.radius[i] + p.radius[j];
        if ((p.x[i] - p.x[j]).squaredNorm() < c * c) {
          ASSERT_TRUE(listed.count({std::min(p.id[i], p.id[j]), std::max(p.id[i], p.id[j])})) << "iteration " << it;
        }
      }
  }
  EXPECT_GT(nl.stats().builds, 3);
}

TEST(NeighborList, HistoryFollowsItsPairThroughResortAndRemoval) {
  std::mt19937_64 rng(3);
  auto p = random_store(rng, 600, 0.6);
  NeighborList nl;
  nl.configure(3, 0.02);
  Walls w;
  nl.build(p, w, Vec3(0, 0, 0), Vec3(1, 1, 1), 0, false);
  // Tag each entry's history with its pair's ids.
  auto tag = [](std::int64_t a, std::int64_t b) { return static_cast<double>(a * 100000 + b); };
  for (std::size_t i = 0; i + 1 < nl.row_start.size(); ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) nl.history[3 * k] = tag(p.id[i], p.id[nl.partner[k]]);
  // Remove every 7th particle, shuffle the order, rebuild with sorting.
  std::vector<char> rm(p.n_owned(), 0);
  for (std::size_t i = 0; i < rm.size(); i += 7) rm[i] = 1;
  p.remove_if(rm);
  std::vector<std::size_t> order(p.n_owned());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  p.permute(order);
  nl.build(p, w, Vec3(0, 0, 0), Vec3(1, 1, 1), 0, true);
  std::size_t carried = 0;
  for (std::size_t i = 0; i + 1 < nl.row_start.size(); ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      EXPECT_EQ(nl.history[3 * k], tag(p.id[i], p.id[nl.partner[k]]));
      ++carried;
    }
  EXPECT_GT(carried, 100u);
}

// Wide size distributions: radii over [rmin, ratio rmin], uniform or bimodal
// (nine small grains to one large). With `bodies`, grains are grouped in
// threes into clumps (body ids); their pairs must be left out.
ParticleStore wide_store(std::mt19937_64& rng, std::size_t n, double L, double rmin, double ratio, bool bimodal,
                         bool bodies) {
  ParticleStore p;
  p.configure(bodies ? FieldSet(Field::Body) : FieldSet{}, 0);
  std::uniform_real_distribution<double> u(0, L), r(rmin, ratio * rmin), c(0, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const double ri = bimodal ? (c(rng) < 0.9 ? rmin : ratio * rmin) : r(rng);
    p.add(static_cast<std::int64_t>(i), Vec3(u(rng), u(rng), u(rng)), Vec3::Zero(), ri, 1.0, 0);
    if (bodies) p.body.back() = static_cast<std::int64_t>(i / 3);
  }
  return p;
}

// Size ratios 10 and 20 go through the search by size class: the same pairs
// as brute force, with one skin and a skin per grain, with ghosts (images
// shifted by the box, as a periodic axis makes) and with clumps.
TEST(NeighborList, WideSizeDistributionsMatchBruteForce) {
  std::mt19937_64 rng(11);
  int checked = 0;
  for (const double ratio : {10.0, 20.0})
    for (const bool bimodal : {false, true})
      for (const bool bodies : {false, true})
        for (const bool ghosts : {false, true})
          for (const double f : {0.0, 0.1}) {
            const double L = 0.4, rmin = 0.004;
            auto p = wide_store(rng, 1200, L, rmin, ratio, bimodal, bodies);
            if (ghosts) {
              const ParticleStore src = p;
              for (std::size_t i = 0; i < src.n_owned(); ++i)
                if (src.x[i].x() < 0.1) p.add_ghost(src, i, Vec3(L, 0, 0));
              ASSERT_GT(p.n_ghost(), 100u);
            }
            const double skin = 0.1 * 2 * ratio * rmin;  // 0.1 of the largest diameter
            NeighborList nl;
            nl.configure(0, skin);
            nl.set_skin_fraction(f);
            Walls w;
            nl.build(p, w, Vec3(0, 0, 0), Vec3(L, L, L), 0, !ghosts);
            const auto want = brute_pairs(p, skin, f);
            EXPECT_EQ(list_pairs(nl, p), want) << "ratio " << ratio << " bimodal " << bimodal << " bodies " << bodies
                                               << " ghosts " << ghosts << " f " << f;
            EXPECT_GT(want.size(), 200u);
            ++checked;
          }
  EXPECT_EQ(checked, 32);
}

// A skin per grain: in a bimodal bed of ratio 10 the small grains list far
// fewer pairs among themselves than with the large grains' skin for all, and
// the trigger still fires before any pair can be missed, while grains move
// and grow.
TEST(NeighborList, SkinPerGrainTriggerFiresBeforeAPairIsMissed) {
  std::mt19937_64 rng(12);
  const double L = 0.3, rmin = 0.004, ratio = 10;
  auto p = wide_store(rng, 2000, L, rmin, ratio, true, false);
  const double skin = 0.1 * 2 * ratio * rmin;
  auto small_pairs = [&](const NeighborList& nl) {
    std::size_t count = 0;
    for (std::size_t i = 0; i + 1 < nl.row_start.size(); ++i)
      for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k)
        count += p.radius[i] == rmin && p.radius[nl.partner[k]] == rmin;
    return count;
  };
  Walls w;
  NeighborList one;
  one.configure(0, skin);
  one.build(p, w, Vec3(0, 0, 0), Vec3(L, L, L), 0, false);
  NeighborList nl;
  nl.configure(0, skin);
  nl.set_skin_fraction(0.1);
  nl.build(p, w, Vec3(0, 0, 0), Vec3(L, L, L), 0, false);
  EXPECT_GT(small_pairs(one), 500u);
  EXPECT_LT(3 * small_pairs(nl), small_pairs(one)) << "a skin per grain keeps the small grains' lists short";
  EXPECT_DOUBLE_EQ(nl.smallest_skin(), 0.1 * 2 * rmin);
  // Each grain keeps a random velocity (straight paths close gaps fastest).
  std::normal_distribution<double> step(0, 0.00003);
  std::vector<Vec3> v(p.size());
  for (auto& vi : v) vi = Vec3(step(rng), step(rng), step(rng));
  for (int it = 0; it < 200; ++it) {
    for (std::size_t i = 0; i < p.size(); ++i) p.x[i] += v[i];
    if (it % 50 == 25) {  // every grain grows a little
      for (auto& r : p.radius) r += 0.00005;
      nl.add_growth(0.00005);
    }
    if (nl.needs_rebuild(p, w, 0)) nl.build(p, w, Vec3(0, 0, 0), Vec3(L, L, L), 0, true);
    const auto listed = list_pairs(nl, p);
    const auto touching = brute_pairs(p, 0.0, 0.0);
    for (const auto& pr : touching) ASSERT_TRUE(listed.count(pr)) << "iteration " << it;
  }
  EXPECT_GT(nl.stats().builds, 5);
  EXPECT_LT(nl.stats().builds, 200);
}

}  // namespace
}  // namespace grains::sim
