// The parallel block's keys: a case that names one of them keeps the
// documented defaults of the others (the rebalance threshold used to become
// 1.2 instead of 1.1 as soon as a case had a parallel block).
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include <omp.h>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"
#include "sim/keys/effect_doc.hpp"
#include "sim/scene/scene_config.hpp"

namespace grains::io {
namespace {

std::string with_parallel(const std::string& block) {
  return R"(domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
materials:
  - {name: glass, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
particles:
  - {material: glass, radius: 0.0005, count: 10, placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}}
time: {dt: 1.0e-6, end: 1.0e-5}
)" + block;
}

// The default `grains docs` prints and the parser reads (KeySpec::def).
double documented_balance_threshold() {
  for (const auto& d : sim::effect_docs())
    if (d.name == "parallel")
      if (const auto* k = d.find("balance_threshold")) return k->default_number;
  ADD_FAILURE() << "parallel.balance_threshold is not documented";
  return 0;
}

TEST(ParallelKeys, BalanceThresholdDefaultsAlike) {
  const double documented = documented_balance_threshold();
  EXPECT_DOUBLE_EQ(documented, 1.1);
  EXPECT_DOUBLE_EQ(sim::SceneConfig{}.parallel.balance_threshold, documented);  // a case without the block
  EXPECT_DOUBLE_EQ(parse_case(with_parallel(""), "case.yaml").scene.parallel.balance_threshold, documented);
  EXPECT_DOUBLE_EQ(parse_case(with_parallel("parallel: {deterministic: false}\n"), "case.yaml")
                       .scene.parallel.balance_threshold,
                   documented);
  EXPECT_DOUBLE_EQ(parse_case(with_parallel("parallel: {decomposition: [1, 1, 2]}\n"), "case.yaml")
                       .scene.parallel.balance_threshold,
                   documented);
  const auto c = parse_case(with_parallel("parallel: {balance_threshold: 1.5, deterministic: true}\n"), "case.yaml");
  EXPECT_DOUBLE_EQ(c.scene.parallel.balance_threshold, 1.5);
  EXPECT_EQ(c.scene.parallel.deterministic, std::optional<bool>(true));
}

// Threads always sum in order: a case that turns the ordered sums off hears
// that it was not done, and with one thread it is done without a word.
TEST(ParallelKeys, UnorderedSumsWithThreadsSayTheyAreIgnored) {
  // OMP_NUM_THREADS and the thread count as they were, however the test ends.
  struct Restore {
    const char* had = std::getenv("OMP_NUM_THREADS");
    std::string saved = had ? had : "";
    int threads = omp_get_max_threads();
    ~Restore() {
      if (had)
        setenv("OMP_NUM_THREADS", saved.c_str(), 1);
      else
        unsetenv("OMP_NUM_THREADS");
      omp_set_num_threads(threads);
    }
  } restore;
  auto run = [](const char* n) {
    setenv("OMP_NUM_THREADS", n, 1);
    omp_set_num_threads(std::atoi(n));
    return make_simulation(parse_case(with_parallel("parallel: {deterministic: false}\n"), "case.yaml"));
  };
  const auto two = run("2");
  EXPECT_TRUE(two.scene.deterministic);
  ASSERT_EQ(two.c.scene.warnings.size(), 1u);
  EXPECT_NE(two.c.scene.warnings[0].find("parallel.deterministic: warning: false is ignored with 2 OpenMP threads"),
            std::string::npos)
      << two.c.scene.warnings[0];
  const auto one = run("1");
  EXPECT_FALSE(one.scene.deterministic);
  EXPECT_TRUE(one.c.scene.warnings.empty());
}

}  // namespace
}  // namespace grains::io
