// Accuracy against time of the spherical decomposition.
//   bench_clump_table MESH [MU [N ...]]      (default: mu 0.25, N = 16 32 64 128)
// For every N: n1 = n2, n3 (and n3 under the seed's step 3 alone), eps, the
// measured Hausdorff distance, the volume error, and the times of each stage.
// Prints a Markdown table (docs/decomposition.md holds a recorded run).

#include "contact/clump/clump_template.hpp"
#include "io/mesh/mesh_reader.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MESH [MU [N ...]]\n", argv[0]);
    return 2;
  }
  using namespace grains;
  const mesh::TriangleMesh m = mesh::load_mesh(argv[1]);
  const double mu = argc > 2 ? std::atof(argv[2]) : 0.25;
  std::vector<int> grids;
  for (int i = 3; i < argc; ++i) grids.push_back(std::atoi(argv[i]));
  if (grids.empty()) grids = {16, 32, 64, 128};
  std::printf("| m | N | n1 = n2 | n3 | n3 (seed step 3) | eps | d_H measured | d_H / eps | volume error | "
              "decomposition s | of which OpenVDB s | exact pass s | mass s | measurement s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int n : grids) {
    clump::ClumpOptions opt;
    opt.decomposition.grid = n;
    opt.decomposition.mu = mu;
    const clump::ClumpTemplate c = clump::build_clump(m, opt);
    const auto& d = c.meta;
    std::printf("| %lld | %d | %zu | %zu | %zu | %.4f | %.4f | %.3f | %+.1f %% | %.2f | %.2f | %.2f | %.2f | %.2f |\n",
                static_cast<long long>(n) * n * n, n, d.n1, d.n3, d.n3_seed_rule(), d.epsilon, d.hausdorff,
                d.hausdorff / d.epsilon, 100 * d.volume_error, d.seconds_decomposition, d.seconds_distance_vdb,
                d.seconds_distance_exact, d.seconds_mass, d.seconds_measurement);
    std::fflush(stdout);
  }
  return 0;
}
