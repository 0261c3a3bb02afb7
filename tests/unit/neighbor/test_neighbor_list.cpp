// The Verlet list holds every pair within r_i + r_j + skin exactly once,
// the displacement trigger fires before a pair can be missed, and contact
// history follows its pair through re-sorting, removals and rebuilds.
#include <gtest/gtest.h>

#include <random>
#include <algorithm>
#include <numeric>
#include <set>

#include "sim/neighbor/neighbor_list.hpp"

namespace grains::sim {
namespace {

ParticleStore random_store(std::mt19937_64& rng, std::size_t n, double L) {
  ParticleStore p;
  p.configure(FieldSet{}, 0);
  std::uniform_real_distribution<double> u(0, L), r(0.02, 0.05);
  for (std::size_t i = 0; i < n; ++i) p.add(static_cast<std::int64_t>(i), Vec3(u(rng), u(rng), u(rng)), Vec3::Zero(), r(rng), 1.0, 0);
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

TEST(NeighborList, MatchesBruteForce) {
  std::mt19937_64 rng(1);
  for (const bool sort : {false, true}) {
    auto p = random_store(rng, 1500, 1.0);
    NeighborList nl;
    const double skin = 0.01;
    nl.configure(0, skin);
    Walls w;
    nl.build(p, w, Vec3(0, 0, 0), Vec3(1, 1, 1), 0, sort);
    std::set<std::pair<std::int64_t, std::int64_t>> brute;
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t j = 0; j < p.size(); ++j) {
        if (p.id[i] >= p.id[j]) continue;
        const double c = p.radius[i] + p.radius[j] + skin;
        if ((p.x[i] - p.x[j]).squaredNorm() < c * c) brute.insert({p.id[i], p.id[j]});
      }
    EXPECT_EQ(list_pairs(nl, p), brute);
    EXPECT_GT(brute.size(), 100u);
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

}  // namespace
}  // namespace grains::sim
