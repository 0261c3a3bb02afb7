// The redistribution behind parallel checkpoints (sim/parallel/id_blocks):
// cuts of the id range, and blocks that, put side by side, are exactly the
// scene gather_scene assembles on rank 0 (particles in id order, the pairs
// with history as CSR rows with partners in that order). Run with
// mpiexec -n 3 (tests/unit/parallel/CMakeLists.txt): uneven blocks.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"
#include "sim/parallel/comm.hpp"
#include "sim/parallel/gather.hpp"
#include "sim/parallel/id_blocks.hpp"

namespace grains::sim {
namespace {

const Comm& comm() { return Comm::world(); }

TEST(IdBlockCuts, EveryIdInOneBlockAndBlocksBalancedWithGaps) {
  ASSERT_GT(comm().size(), 1) << "run under mpiexec -n 3";
  // Rank r holds every P-th id of 0..2999 and of 1,000,000..1,000,899 (a gap
  // of ~1e6 ids, as after many lost particles); the last rank holds none of
  // the second range.
  const int P = comm().size(), r = comm().rank();
  std::vector<std::int64_t> ids;
  for (std::int64_t i = r; i < 3000; i += P) ids.push_back(i);
  if (r != P - 1)
    for (std::int64_t i = 1000000 + r; i < 1000900; i += P) ids.push_back(i);
  const auto cuts = id_block_cuts(comm(), ids);
  ASSERT_EQ(cuts.size(), static_cast<std::size_t>(P + 1));
  EXPECT_EQ(cuts.front(), 0);
  std::int64_t largest = 0;
  for (auto id : ids) largest = std::max(largest, id);
  EXPECT_EQ(cuts.back(), comm().max(largest) + 1);
  std::vector<std::int64_t> per_block(static_cast<std::size_t>(P), 0);
  for (auto id : ids) {
    int owners = 0;
    for (int b = 0; b < P; ++b)
      if (cuts[b] <= id && id < cuts[b + 1]) ++owners, ++per_block[static_cast<std::size_t>(b)];
    EXPECT_EQ(owners, 1) << "id " << id;
  }
  comm().sum_in_place(per_block);
  std::int64_t n = 0;
  for (auto c : per_block) n += c;
  for (auto c : per_block) EXPECT_NEAR(static_cast<double>(c), static_cast<double>(n) / P, 0.02 * n) << "unbalanced";
}

TEST(IdBlockCuts, NoIdsAnywhereGivesEmptyBlocks) {
  const auto cuts = id_block_cuts(comm(), {});
  for (auto c : cuts) EXPECT_EQ(c, 0);
}

// Bytes of every field of particle i.
std::vector<char> record(ParticleStore& p, std::size_t i) {
  std::vector<char> b;
  p.pack(i, b);
  return b;
}

TEST(IdBlocks, SideBySideTheyAreTheGatheredScene) {
  std::ifstream in(std::string(GRAINS_SOURCE_DIR) + "/tests/integration/restart_case.yaml");
  std::stringstream text;
  text << in.rdbuf();
  // 600 frictional spheres packed low in the box, falling onto a rising
  // floor: many contacts with history after 1500 steps, some between
  // particles of different ranks.
  auto sim = io::make_simulation(
      io::parse_case(text.str(), "restart_case.yaml",
                     {"particles.0.count=600", "particles.0.placement.region.max=[0.012,0.012,0.006]",
                      "parallel.deterministic=true"}));
  auto& s = sim.scene;
  ASSERT_TRUE(s.exchange);
  sim.pipeline.initialize(s);
  for (int k = 0; k < 1500; ++k) sim.pipeline.step(s);

  auto g = gather_scene(s);
  auto b = id_blocks(s);
  const std::size_t n = b.particles.n_owned();
  // Offsets are exclusive scans of the block sizes.
  const auto sizes = comm().all_gather(static_cast<std::int64_t>(n));
  std::int64_t before = 0, total = 0;
  for (int r = 0; r < comm().size(); ++r) {
    if (r < comm().rank()) before += sizes[static_cast<std::size_t>(r)];
    total += sizes[static_cast<std::size_t>(r)];
  }
  EXPECT_EQ(b.particle_offset, static_cast<std::size_t>(before));
  EXPECT_EQ(b.particle_total, static_cast<std::size_t>(total));
  EXPECT_EQ(b.row_start.size(), n + 1);
  EXPECT_EQ(b.row_start.front(), b.entry_offset);
  EXPECT_EQ(b.row_start.back(), b.entry_offset + b.partner.size());
  EXPECT_EQ(b.history.size(), b.partner.size() * static_cast<std::size_t>(s.neighbors.history_size()));

  // Everything a rank holds, in one buffer for rank 0.
  std::vector<char> mine;
  auto put = [&mine](const void* p, std::size_t bytes) {
    mine.insert(mine.end(), static_cast<const char*>(p), static_cast<const char*>(p) + bytes);
  };
  const std::size_t m = b.partner.size();
  put(&n, sizeof n);
  put(&m, sizeof m);
  for (std::size_t i = 0; i < n; ++i) {
    const auto rec = record(b.particles, i);
    put(rec.data(), rec.size());
  }
  put(b.row_start.data(), n * sizeof(std::uint32_t));  // the closing entry comes from the last rank
  put(b.partner.data(), m * sizeof(std::uint32_t));
  put(b.history.data(), b.history.size() * sizeof(double));
  const auto parts = comm().gather(mine);
  if (!comm().root()) return;

  auto& gp = g.particles;
  const auto& nl = g.neighbors;
  ASSERT_EQ(gp.n_owned(), static_cast<std::size_t>(total));
  ASSERT_GT(nl.partner.size(), 100u) << "the scene should have many contacts with history";
  const std::size_t rec_bytes = gp.record_bytes();
  const std::size_t H = static_cast<std::size_t>(s.neighbors.history_size());
  std::size_t row = 0, entry = 0;
  for (const auto& part : parts) {
    const char* q = part.data();
    std::size_t pn = 0, pm = 0;
    std::memcpy(&pn, q, sizeof pn), q += sizeof pn;
    std::memcpy(&pm, q, sizeof pm), q += sizeof pm;
    for (std::size_t i = 0; i < pn; ++i, q += rec_bytes)
      ASSERT_EQ(std::memcmp(q, record(gp, row + i).data(), rec_bytes), 0) << "particle row " << row + i;
    for (std::size_t i = 0; i < pn; ++i, q += sizeof(std::uint32_t)) {
      std::uint32_t v;
      std::memcpy(&v, q, sizeof v);
      ASSERT_EQ(v, nl.row_start[row + i]) << "row_start " << row + i;
    }
    for (std::size_t k = 0; k < pm; ++k, q += sizeof(std::uint32_t)) {
      std::uint32_t v;
      std::memcpy(&v, q, sizeof v);
      ASSERT_EQ(v, nl.partner[entry + k]) << "partner " << entry + k;
    }
    ASSERT_EQ(std::memcmp(q, nl.history.data() + entry * H, pm * H * sizeof(double)), 0) << "history";
    row += pn;
    entry += pm;
  }
  EXPECT_EQ(row, gp.n_owned());
  EXPECT_EQ(entry, nl.partner.size());
  EXPECT_EQ(nl.row_start.back(), entry);
}

}  // namespace
}  // namespace grains::sim

int main(int argc, char** argv) {
  grains::sim::Comm::init(&argc, &argv, true);
  ::testing::InitGoogleTest(&argc, argv);
  if (!grains::sim::Comm::world().root()) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int rc = RUN_ALL_TESTS();
  const bool failed = grains::sim::Comm::world().any(rc != 0);
  grains::sim::Comm::finalize();
  return failed ? 1 : 0;
}
