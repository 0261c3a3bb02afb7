// Under MPI with more than one rank, integrator: arkode is refused at set-up
// with a clear message (the ARKODE driver is serial / OpenMP only); Verlet
// cases are not affected. Run with mpiexec -n 2 (tests/unit/arkode/CMakeLists.txt).
#include <gtest/gtest.h>
#include <mpi.h>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"

namespace grains::io {
namespace {

const std::string kCase = R"(domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
materials:
  - {name: glass, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
particles:
  - {material: glass, radius: 0.0005, count: 4, placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}}
time: {dt: 1.0e-6, end: 1.0e-5, integrator: arkode}
)";

TEST(ArkodeMpi, RefusedOnSeveralRanks) {
  int size = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ASSERT_GT(size, 1) << "run under mpiexec -n 2";
  try {
    (void)make_simulation(parse_case(kCase, "case.yaml"));
    FAIL() << "accepted on " << size << " ranks";
  } catch (const sim::SetupError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("case.yaml:6:45: integrator: arkode runs on one MPI rank"), std::string::npos) << m;
    EXPECT_NE(m.find("this run has " + std::to_string(size) + " ranks"), std::string::npos) << m;
  }
  EXPECT_NO_THROW((void)make_simulation(parse_case(kCase, "case.yaml", {"time.integrator=verlet"})));
}

}  // namespace
}  // namespace grains::io

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int rc = RUN_ALL_TESTS();
  int worst = 0;
  MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return worst;
}
