// NUFFT and overlap-field benchmarks (docs/nfft.md records the figures).
//
//   bench_nufft --benchmark_filter=Type1   etc.
//
// Arguments of the NUFFT cases: N per dimension, M points, -log10(eps),
// threads, 100 * upsampling. Accuracy counters compare with an eps = 1e-14
// transform of the same points (itself checked against direct sums in the
// unit tests).
#include <benchmark/benchmark.h>

#include <cmath>
#include <complex>
#include <map>
#include <mutex>
#include <numbers>
#include <random>
#include <tuple>
#include <vector>

#include "contact/correlation/ball_kernels.hpp"
#include "contact/correlation/nufft3d.hpp"
#include "contact/correlation/overlap_field.hpp"
#include "contact/correlation/pruned_fft.hpp"
#include "contact/correlation/solid_fraction.hpp"
#include "contact/correlation/spreader.hpp"
#include "contact/correlation/truncated_overlap.hpp"

namespace gc = grains::correlation;
using Complex = std::complex<double>;

namespace {

struct Points {
  std::vector<double> x, y, z;
  std::vector<Complex> c;
};

const Points& points(std::size_t m) {
  static std::map<std::size_t, Points> cache;
  auto it = cache.find(m);
  if (it != cache.end()) return it->second;
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-std::numbers::pi, std::numbers::pi), v(-1, 1);
  Points p;
  p.x.resize(m); p.y.resize(m); p.z.resize(m); p.c.resize(m);
  for (std::size_t j = 0; j < m; ++j) {
    p.x[j] = u(rng); p.y[j] = u(rng); p.z[j] = u(rng);
    p.c[j] = Complex(v(rng), v(rng));
  }
  return cache.emplace(m, std::move(p)).first->second;
}

// Reference type-1 result at eps = 1e-14 (cached per N, M).
const std::vector<Complex>& reference_type1(int n, std::size_t m) {
  static std::map<std::pair<int, std::size_t>, std::vector<Complex>> cache;
  auto key = std::make_pair(n, m);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const Points& p = points(m);
  gc::NufftOptions opt;
  opt.threads = 2;
  gc::Nufft3d plan({n, n, n}, 1e-14, opt);
  plan.set_points(p.x, p.y, p.z);
  std::vector<Complex> f(plan.num_modes());
  plan.type1(p.c, f, -1);
  return cache.emplace(key, std::move(f)).first->second;
}

double rel_l2(const std::vector<Complex>& a, const std::vector<Complex>& b) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num += std::norm(a[i] - b[i]);
    den += std::norm(b[i]);
  }
  return std::sqrt(num / den);
}

gc::NufftOptions options(const benchmark::State& st) {
  gc::NufftOptions opt;
  opt.threads = static_cast<int>(st.range(3));
  opt.upsampling = st.range(4) / 100.0;
  return opt;
}

}  // namespace

static void BM_Type1(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const std::size_t m = static_cast<std::size_t>(st.range(1));
  const double eps = std::pow(10.0, -static_cast<double>(st.range(2)));
  const Points& p = points(m);
  gc::Nufft3d plan({n, n, n}, eps, options(st));
  std::vector<Complex> f(plan.num_modes());
  for (auto _ : st) {
    plan.set_points(p.x, p.y, p.z);  // sorting counted, as in a one-shot call
    plan.type1(p.c, f, -1);
    benchmark::ClobberMemory();
  }
  st.counters["width"] = plan.kernel().width;
  st.counters["fine"] = plan.fine()[0];
  if (n <= 64) st.counters["rel_err"] = rel_l2(f, reference_type1(n, m));
}

static void BM_Type2(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const std::size_t m = static_cast<std::size_t>(st.range(1));
  const double eps = std::pow(10.0, -static_cast<double>(st.range(2)));
  const Points& p = points(m);
  gc::Nufft3d plan({n, n, n}, eps, options(st));
  std::vector<Complex> f(plan.num_modes(), Complex(1.0, 0.5)), c(m);
  for (auto _ : st) {
    plan.set_points(p.x, p.y, p.z);
    plan.type2(f, c, +1);
    benchmark::ClobberMemory();
  }
  st.counters["width"] = plan.kernel().width;
}

// The FFT of the fine grid alone as type 1 runs it (pruned, staged).
static void BM_FineFFT(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  gc::Nufft3d plan({n, n, n}, 1e-6, options(st));
  for (auto _ : st) plan.execute_fine_fft(-1);
  st.counters["fine"] = plan.fine()[0];
}

// For comparison: one FFTW_ESTIMATE plan of the whole 3D fine grid.
static void BM_FineFFTW3d(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const int fine = gc::fine_grid_size(n, st.range(4) / 100.0, 8);
  const std::array<int, 3> f = {fine, fine, fine};
  gc::FftwBuffer grid(2 * static_cast<std::size_t>(fine) * fine * fine);
  const gc::FftwPlan plan =
      gc::plan_c2c_3d(f, grid.as_complex(), FFTW_FORWARD, static_cast<int>(st.range(3)), FFTW_ESTIMATE);
  for (auto _ : st) plan.execute();
  st.counters["fine"] = fine;
}

static void NufftArgs(benchmark::internal::Benchmark* b) {
  for (int threads : {1, 2})
    for (int n : {64, 128})
      for (int e : {3, 6, 9}) b->Args({n, 1000000, e, threads, 200});
  for (int e : {3, 6}) b->Args({64, 1000000, e, 1, 125});  // upsampling 1.25
  b->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();
}

static void FftArgs(benchmark::internal::Benchmark* b) {
  for (int threads : {1, 2})
    for (int n : {64, 128}) b->Args({n, 0, 6, threads, 200});
  b->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();
}

BENCHMARK(BM_Type1)->Apply(NufftArgs);
BENCHMARK(BM_Type2)->Apply(NufftArgs);
BENCHMARK(BM_FineFFT)->Apply(FftArgs);
BENCHMARK(BM_FineFFTW3d)->Apply(FftArgs);

// The real FFTs of the overlap fields: args n (real grid per side), K (modes
// needed per axis), direction (0: r2c, 1: c2r), threads. Staged and pruned
// (PrunedRealFft3d, in place) against one FFTW_ESTIMATE 3D plan.
static void BM_RealFFT(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0)), K = static_cast<int>(st.range(1));
  const std::array<int, 3> N = {n, n, n}, KK = {K, K, K};
  gc::FftwBuffer a(2 * static_cast<std::size_t>(n / 2 + 1) * n * n);
  gc::PrunedRealFft3d fft(N, KK, a.data(), static_cast<int>(st.range(3)), FFTW_ESTIMATE);
  for (auto _ : st) {
    if (st.range(2) == 0)
      fft.forward(a.data());
    else
      fft.backward(a.data());
  }
}

static void BM_RealFFTW3d(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  gc::FftwBuffer a(2 * static_cast<std::size_t>(n / 2 + 1) * n * n);
  gc::fftw_threads_init_once();
  fftw_plan p;
  {
    std::lock_guard<std::mutex> lock(gc::fftw_planner_mutex());
    fftw_plan_with_nthreads(static_cast<int>(st.range(3)));
    p = st.range(2) == 0 ? fftw_plan_dft_r2c_3d(n, n, n, a.data(), a.as_complex(), FFTW_ESTIMATE)
                         : fftw_plan_dft_c2r_3d(n, n, n, a.as_complex(), a.data(), FFTW_ESTIMATE);
  }
  const gc::FftwPlan plan(p);
  for (auto _ : st) plan.execute();
}

static void RealFftArgs(benchmark::internal::Benchmark* b) {
  // The insertion bench's boxes: a 216^3 fine grid for the scene spectrum
  // (r2c), a 160^3 field grid (c2r), 80 modes per axis.
  for (int threads : {1, 2}) {
    b->Args({216, 80, 0, threads});
    b->Args({160, 80, 1, threads});
  }
  b->Unit(benchmark::kMillisecond)->Iterations(5)->UseRealTime();
}

BENCHMARK(BM_RealFFT)->Apply(RealFftArgs);
BENCHMARK(BM_RealFFTW3d)->Apply(RealFftArgs);

// Solid fraction of a dense random (overlapping) bed: args balls, grid
// nodes per side, -log10(tol), threads. Smoothing length = grid spacing.
static void BM_SolidFraction(benchmark::State& st) {
  const std::size_t nb = static_cast<std::size_t>(st.range(0));
  const int n = static_cast<int>(st.range(1));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> c(3 * nb), r(nb);
  for (auto& v : c) v = u(rng);
  for (std::size_t i = 0; i < nb; ++i) r[i] = (i % 2) ? 0.01 : 0.015;
  gc::GridSpec g;
  g.dims = {n, n, n};
  g.spacing = {1.0 / n, 1.0 / n, 1.0 / n};
  gc::SolidFractionOptions opt;
  opt.tolerance = std::pow(10.0, -static_cast<double>(st.range(2)));
  opt.threads = static_cast<int>(st.range(3));
  gc::SolidFractionInfo info;
  for (auto _ : st) {
    auto f = solid_fraction_field(gc::BallSet{c, r}, g, opt, &info);
    benchmark::DoNotOptimize(f.data());
  }
  st.counters["modes_per_axis"] = 2 * info.max_mode[0] + 1;
}
BENCHMARK(BM_SolidFraction)
    ->Args({100000, 64, 6, 1})
    ->Args({100000, 64, 6, 2})
    ->Args({100000, 128, 6, 2})
    ->Args({100000, 64, 3, 2})
    ->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

// Overlap field of a 4-ball clump against a random bed of 20000 balls.
static void BM_OverlapField(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::size_t nb = 20000;
  std::vector<double> c(3 * nb), r(nb, 0.012);
  for (auto& v : c) v = u(rng);
  const std::vector<double> sc = {-0.01, 0, 0, 0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01},
                            sr = {0.01, 0.01, 0.008, 0.008};
  gc::GridSpec g;
  g.dims = {n, n, n};
  g.spacing = {1.0 / n, 1.0 / n, 1.0 / n};
  gc::OverlapFieldOptions opt;
  opt.threads = static_cast<int>(st.range(1));
  for (auto _ : st) {
    auto f = translational_overlap_field(gc::BallSet{c, r}, gc::BallSet{sc, sr}, gc::kIdentityRotation, g, opt);
    benchmark::DoNotOptimize(f.data());
  }
}
BENCHMARK(BM_OverlapField)->Args({64, 2})->Args({128, 2})->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

// Truncated-mode overlap query of two 20-ball clumps: time and error
// against the exact lens sum, as functions of m'.
static void BM_TruncatedQuery(benchmark::State& st) {
  const std::size_t mp = static_cast<std::size_t>(st.range(0));
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  std::vector<double> ac(60), ar(20, 0.05), bc(60), br(20, 0.04);
  for (auto& v : ac) v = u(rng);
  for (auto& v : bc) v = u(rng);
  const gc::BallSet a{ac, ar}, b{bc, br};
  const std::array<double, 3> tmax = {0.15, 0.15, 0.15};
  static const gc::TruncatedOverlap* q = nullptr;
  if (!q) {
    gc::TruncatedOverlapOptions opt;
    opt.max_mode = {32, 32, 32};
    opt.threads = 1;
    q = new gc::TruncatedOverlap(a, b, gc::TruncatedOverlap::safe_period(a, b, tmax), opt);
  }
  std::vector<std::array<double, 3>> ts;
  std::vector<double> exact;
  std::uniform_real_distribution<double> ut(-0.15, 0.15);
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
  std::size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(q->overlap(ts[i++ % ts.size()], mp));
  }
  double e2 = 0, vmax = 0;
  for (std::size_t k = 0; k < ts.size(); ++k) {
    e2 += std::pow(q->overlap(ts[k], mp) - exact[k], 2);
    vmax = std::max(vmax, exact[k]);
  }
  st.counters["rms_err_rel"] = std::sqrt(e2 / ts.size()) / vmax;
  st.counters["modes_total"] = static_cast<double>(q->num_modes());
}
BENCHMARK(BM_TruncatedQuery)->RangeMultiplier(8)->Range(64, 1 << 17)->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv) {
  benchmark::AddCustomContext("spreading", gc::spreading_instruction_set());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
