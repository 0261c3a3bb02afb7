// The cost of one contact evaluation of each normal law composed with
// Mindlin's tangential spring (sim/laws/contact_law.hpp), the kernel a pair
// stage runs per touching pair. 4096 contacts of a material pair, R* and m*
// of 0.5 mm grains, overlaps in (0, 2e-6] m drifting by a small relative
// amount per "step" (one benchmark iteration sweeps all contacts), as in a
// settled bed; `drift` (the argument, in 1e-6 of the overlap per step) sets
// how far JKR's Newton iteration starts from its root. DMT and JKR with
// w = 0.1 J/m^2 (surface_energy 0.05).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "sim/laws/contact_law.hpp"
#include "sim/laws/material.hpp"

namespace {

using namespace grains::sim;

template <class N>
void BM_Contact(benchmark::State& state) {
  using Law = ContactLaw<N, SpringTangential, NoRolling, NoCohesion>;
  Material m{"m", 2500, 1e7, 0.3, 0.5, 0.5, 0.0, 0.0};
  m.surface_energy = N::name == std::string("hertz") ? 0.0 : 0.05;
  const PairTable table({m}, {}, NormalLawChoice{N::name, LawValues{}});
  const PairParams& p = table(0, 0);
  const int n = 4096;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<grains::contact::ContactGeometry> g(n);
  std::vector<Eigen::Vector3d> v(n);
  std::vector<double> base(n), phase(n), wave(n), hist(static_cast<std::size_t>(n) * Law::history_size, 0.0);
  for (int k = 0; k < n; ++k) {
    g[k].normal = Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
    g[k].radius = 2.5e-4;
    base[k] = 2e-6 * (0.05 + u(rng));
    phase[k] = 6.283 * u(rng);
    wave[k] = 0.5 * std::cos(phase[k]);
    v[k] = 1e-3 * Eigen::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
  }
  const double drift = 1e-6 * static_cast<double>(state.range(0));
  const double mass = 0.5 * 2500 * 4.0 / 3.0 * M_PI * 1.25e-10;
  long step = 0;
  for (auto _ : state) {
    const double s = std::sin(drift * static_cast<double>(step++));
    for (int k = 0; k < n; ++k) {
      g[k].overlap = base[k] * (1.0 + s * wave[k]);
      const auto r = Law::evaluate(g[k], v[k], Eigen::Vector3d::Zero(), mass, p, 1e-6,
                                   hist.data() + static_cast<std::size_t>(k) * Law::history_size);
      benchmark::DoNotOptimize(r.force);
    }
  }
  state.SetItemsProcessed(state.iterations() * n);
}

BENCHMARK(BM_Contact<HertzNormal>)->Arg(100);
BENCHMARK(BM_Contact<DmtNormal>)->Arg(100);
BENCHMARK(BM_Contact<JkrNormal>)->Arg(1)->Arg(100)->Arg(10000);

}  // namespace

BENCHMARK_MAIN();
