// The rank grid (sim/parallel/decomposition.hpp): its shape, owners and
// neighbours, the quantile balance and its limits. One process; the rank
// count is a parameter of the grid, not of the run.
#include <gtest/gtest.h>

#include <random>

#include "sim/neighbor/neighbor_list.hpp"
#include "sim/parallel/decomposition.hpp"
#include "sim/parallel/exchange.hpp"
#include "sim/scene/scene.hpp"

namespace grains::sim {
namespace {

Domain box(Vec3 hi, std::array<bool, 3> periodic = {false, false, false}) {
  Domain d;
  d.lo = Vec3::Zero();
  d.hi = hi;
  d.periodic = periodic;
  return d;
}

TEST(Decomposition, SplitsTheLongestDimensionFirst) {
  const Decomposition tall(box({1, 1, 8}), 4, 0.1);
  EXPECT_EQ(tall.dims(), (std::array<int, 3>{1, 1, 4}));
  const Decomposition flat(box({4, 4, 1}), 4, 0.1);
  EXPECT_EQ(flat.dims(), (std::array<int, 3>{2, 2, 1}));
  const Decomposition forced(box({4, 4, 1}), 4, 0.1, {4, 1, 1});
  EXPECT_EQ(forced.dims(), (std::array<int, 3>{4, 1, 1}));
}

TEST(Decomposition, RefusesSlabsNarrowerThanTheGhostCutoff) {
  EXPECT_THROW(Decomposition(box({1, 1, 1}), 4, 0.6), std::runtime_error);
  try {
    Decomposition(box({1, 1, 1}), 3, 0.5);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("at least the ghost cut-off"), std::string::npos) << e.what();
  }
}

TEST(Decomposition, OwnersAndNeighbours) {
  const Decomposition d(box({2, 2, 2}), 8, 0.1);
  ASSERT_EQ(d.dims(), (std::array<int, 3>{2, 2, 2}));
  for (int r = 0; r < 8; ++r) {
    const Vec3 c = 0.5 * (d.lo(r) + d.hi(r));
    EXPECT_EQ(d.owner(c), r);
    EXPECT_EQ(d.rank_at(d.coords(r)), r);
  }
  EXPECT_EQ(d.owner(Vec3(2, 2, 2)), 7);  // the upper faces belong to the last slab
  EXPECT_EQ(d.owner(Vec3(-1, 0.5, 0.5)), 0);  // outside: clamped
  bool wraps = true;
  EXPECT_EQ(d.neighbor(0, 0, +1, wraps), 1);
  EXPECT_FALSE(wraps);
  EXPECT_EQ(d.neighbor(0, 0, -1, wraps), -1);  // non-periodic face
  const Decomposition p(box({2, 2, 2}, {true, false, false}), 8, 0.1, {2, 2, 2});
  EXPECT_EQ(p.neighbor(0, 0, -1, wraps), 1);
  EXPECT_TRUE(wraps);
}

TEST(Decomposition, BalanceEqualisesABottomHeavyBed) {
  // 90 % of the particles in the lowest tenth of a tall box.
  Decomposition d(box({1, 1, 10}), 4, 0.2);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> x;
  for (int i = 0; i < 20000; ++i) x.emplace_back(u(rng), u(rng), i % 10 ? u(rng) : 10 * u(rng));
  // Uniform cuts at z = 2.5, 5, 7.5: the lowest slab holds ~92 %.
  auto counts = [&] {
    std::array<int, 4> c{};
    for (const auto& xi : x) ++c[static_cast<std::size_t>(d.owner(xi))];
    return c;
  };
  const auto before = counts();
  EXPECT_GT(before[0], 17000);
  const Comm one;
  EXPECT_TRUE(d.balance(x, x.size(), one));
  for (int c : counts()) EXPECT_NEAR(c, 5000, 300);
  // Cut planes stay at least the minimum width apart.
  const auto& z = d.cuts()[2];
  for (std::size_t k = 1; k < z.size(); ++k) EXPECT_GE(z[k] - z[k - 1], 0.2 - 1e-12);
}

// Cuts saved by a checkpoint are taken over by a grid of the same shape
// (a continuation on the same rank count), and refused otherwise.
TEST(Decomposition, TakesSavedCutsOfTheSameGridOnly) {
  Decomposition d(box({1, 1, 8}), 4, 0.1);
  auto cuts = d.cuts();
  ASSERT_EQ(cuts[2].size(), 5u);
  cuts[2] = {0, 0.5, 1.25, 3, 8};
  EXPECT_TRUE(d.set_cuts(cuts));
  EXPECT_EQ(d.cuts()[2], cuts[2]);
  EXPECT_EQ(d.owner({0.5, 0.5, 1.0}), d.rank_at({0, 0, 1}));
  auto fewer = cuts;
  fewer[2] = {0, 2, 8};  // another rank count
  EXPECT_FALSE(d.set_cuts(fewer));
  auto other_box = cuts;
  other_box[2].back() = 9;  // another domain
  EXPECT_FALSE(d.set_cuts(other_box));
  auto unordered = cuts;
  unordered[2] = {0, 2, 1.5, 3, 8};
  EXPECT_FALSE(d.set_cuts(unordered));
  EXPECT_EQ(d.cuts()[2], cuts[2]);  // unchanged by the refusals
}

TEST(Decomposition, BalanceKeepsTheMinimumWidth) {
  Decomposition d(box({1, 1, 1}), 4, 0.2);
  std::vector<Vec3> x(1000, Vec3(0.5, 0.5, 0.01));  // everything at one height
  const Comm one;
  d.balance(x, x.size(), one);
  const auto& z = d.cuts()[2];
  for (std::size_t k = 1; k < z.size(); ++k) EXPECT_GE(z[k] - z[k - 1], 0.2 - 1e-12);
}

TEST(Decomposition, BalanceFollowsTheWorkWeights) {
  // Uniform in z, but the lower half three times as costly: the cut of two
  // ranks goes where the work halves, z = 1/3, not at the median z = 1/2.
  Decomposition d(box({1, 1, 1}), 2, 0.05);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3> x;
  std::vector<double> w;
  for (int i = 0; i < 40000; ++i) {
    x.emplace_back(u(rng), u(rng), u(rng));
    w.push_back(x.back().z() < 0.5 ? 3.0 : 1.0);
  }
  const Comm one;
  EXPECT_TRUE(d.balance(x, x.size(), one, w.data()));
  EXPECT_NEAR(d.cuts()[2][1], 1.0 / 3.0, 0.01);
  EXPECT_TRUE(d.balance(x, x.size(), one));
  EXPECT_NEAR(d.cuts()[2][1], 0.5, 0.01);
}

TEST(Exchange, WorkWeightsCountTheListEntriesOfEachParticle) {
  // A chain of three touching spheres and a lone one: the middle sphere
  // takes part in two entries, the ends in one, the lone one in none; an
  // entry between two owned particles counts half for each.
  ParticleStore p;
  p.configure(FieldSet{}, 0);
  for (int i = 0; i < 3; ++i) p.add(i, Vec3(0.1 + 0.1 * i, 0.5, 0.5), Vec3::Zero(), 0.05, 1.0, 0);
  p.add(3, Vec3(0.9, 0.9, 0.9), Vec3::Zero(), 0.05, 1.0, 0);
  NeighborList nl;
  nl.configure(0, 0.01);
  Walls walls;
  // Before any build the list says nothing: one unit each; a rank without
  // particles has no weights.
  EXPECT_EQ(Exchange::work_weights(p, nl), std::vector<double>(4, 1.0));
  EXPECT_TRUE(Exchange::work_weights(ParticleStore{}, nl).empty());
  nl.build(p, walls, Vec3(0, 0, 0), Vec3(1, 1, 1), 0, false);
  std::vector<double> by_id(4);
  const auto w = Exchange::work_weights(p, nl);
  ASSERT_EQ(w.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) by_id[static_cast<std::size_t>(p.id[i])] = w[i];
  EXPECT_EQ(by_id, (std::vector<double>{1.5, 2.0, 1.5, 1.0}));
}

}  // namespace
}  // namespace grains::sim
