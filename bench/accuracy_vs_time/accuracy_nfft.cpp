// NFFT accuracy against time for the accuracy-vs-time report
// (bench/accuracy_vs_time/run.py), one thread:
//  * BM_FieldTolerance/k: the translational overlap field of a 4-ball clump
//    against a random bed of 100000 balls on a 48^3 grid at NUFFT tolerance
//    10^-k; error = max |V - V_ref| / max V_ref with V_ref the same field at
//    1e-13 (same modes: the NUFFT error alone, not the mode truncation).
//  * BM_TruncatedQuery/m': one overlap query of two 20-ball clumps from the
//    m' dominant modes (seed's Figs. 7-9); error against the exact lens sums
//    over 64 translations (rms and max, relative to the largest overlap).
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>
#include <vector>

#include "contact/correlation/ball_kernels.hpp"
#include "contact/correlation/overlap_field.hpp"
#include "contact/correlation/truncated_overlap.hpp"

namespace gc = grains::correlation;

namespace {

struct FieldScene {
  std::vector<double> c, r;
  std::vector<double> sc{-0.01, 0, 0, 0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01}, sr{0.01, 0.01, 0.008, 0.008};
  gc::GridSpec grid;
  FieldScene() {
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const std::size_t nb = 100000;
    c.resize(3 * nb);
    r.assign(nb, 0.01);
    for (auto& v : c) v = u(rng);
    grid.dims = {48, 48, 48};
    grid.spacing = {1.0 / 48, 1.0 / 48, 1.0 / 48};
  }
  std::vector<double> field(double eps) const {
    gc::OverlapFieldOptions opt;
    opt.tolerance = eps;
    opt.threads = 1;
    return gc::translational_overlap_field(gc::BallSet{c, r}, gc::BallSet{sc, sr}, gc::kIdentityRotation, grid, opt);
  }
};

const FieldScene& scene() {
  static const FieldScene s;
  return s;
}

void BM_FieldTolerance(benchmark::State& st) {
  const double eps = std::pow(10.0, -static_cast<double>(st.range(0)));
  static const std::vector<double> ref = scene().field(1e-13);
  std::vector<double> f;
  for (auto _ : st) {
    f = scene().field(eps);
    benchmark::DoNotOptimize(f.data());
  }
  double err = 0, vmax = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    err = std::max(err, std::abs(f[i] - ref[i]));
    vmax = std::max(vmax, std::abs(ref[i]));
  }
  st.counters["max_err_rel"] = err / vmax;
}
BENCHMARK(BM_FieldTolerance)->DenseRange(2, 12, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

struct QueryScene {
  std::vector<double> ac, ar, bc, br;
  std::vector<std::array<double, 3>> ts;
  std::vector<double> exact;
  const gc::TruncatedOverlap* q = nullptr;
  QueryScene() : ac(60), ar(20, 0.05), bc(60), br(20, 0.04) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-0.1, 0.1), ut(-0.15, 0.15);
    for (auto& v : ac) v = u(rng);
    for (auto& v : bc) v = u(rng);
    const gc::BallSet a{ac, ar}, b{bc, br};
    gc::TruncatedOverlapOptions opt;
    opt.max_mode = {32, 32, 32};
    opt.threads = 1;
    q = new gc::TruncatedOverlap(a, b, gc::TruncatedOverlap::safe_period(a, b, {0.15, 0.15, 0.15}), opt);
    for (int i = 0; i < 64; ++i) {
      ts.push_back({ut(rng), ut(rng), ut(rng)});
      double v = 0;
      for (int j = 0; j < 20; ++j)
        for (int k = 0; k < 20; ++k) {
          const double dx = ac[3 * j] - bc[3 * k] - ts.back()[0], dy = ac[3 * j + 1] - bc[3 * k + 1] - ts.back()[1],
                       dz = ac[3 * j + 2] - bc[3 * k + 2] - ts.back()[2];
          v += gc::lens_volume(std::sqrt(dx * dx + dy * dy + dz * dz), ar[j], br[k]);
        }
      exact.push_back(v);
    }
  }
};

void BM_TruncatedQuery(benchmark::State& st) {
  static const QueryScene s;
  const std::size_t mp = static_cast<std::size_t>(st.range(0));
  std::size_t i = 0;
  for (auto _ : st) benchmark::DoNotOptimize(s.q->overlap(s.ts[i++ % s.ts.size()], mp));
  double e2 = 0, emax = 0, vmax = 0;
  for (std::size_t k = 0; k < s.ts.size(); ++k) {
    const double e = std::abs(s.q->overlap(s.ts[k], mp) - s.exact[k]);
    e2 += e * e;
    emax = std::max(emax, e);
    vmax = std::max(vmax, s.exact[k]);
  }
  st.counters["rms_err_rel"] = std::sqrt(e2 / static_cast<double>(s.ts.size())) / vmax;
  st.counters["max_err_rel"] = emax / vmax;
  st.counters["modes_total"] = static_cast<double>(s.q->num_modes());
}
BENCHMARK(BM_TruncatedQuery)->RangeMultiplier(4)->Range(16, 1 << 17)->Unit(benchmark::kNanosecond);

}  // namespace

BENCHMARK_MAIN();
