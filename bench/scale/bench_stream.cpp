// What one core can stream from and to memory: the floor under the stages
// of a bed too large for the caches (issue 26, flat throughput in N). The
// pair stage of a settled bed walks its list in order: the partners, the
// may-touch bytes and the tangential springs (read, then written in place),
// and each grain's fields once (read) and its force and torque (read and
// written). At 10^6 grains these are hundreds of MB per step, far past the
// caches, so a step cannot take less than their bytes over what these loops
// measure. Four loops over one array of doubles of the argument's size:
//   Read    s += a[i]                     (bytes read)
//   Update  a[i] = a[i] * c + d           (read and written in place)
//   Copy    b[i] = a[i]                   (read one, write another)
//   Triad   a[i] = b[i] + c * d[i]        (STREAM's triad: two read, one written)
// The counter bytes_per_second counts the bytes the loop asks for (an update
// counts its 8 bytes twice), not the write-allocate reads the cache adds.
// Sizes: 2 MiB (in L2/L3 on the machines in bench/RESULTS.md) and 256, 512
// MiB (past every cache). Run: build/bench/scale/bench_stream.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace {

std::size_t doubles(const benchmark::State& state) {
  return static_cast<std::size_t>(state.range(0)) * (std::size_t{1} << 20) / sizeof(double);
}

// The bytes the loop asks for per iteration, as a rate.
void count_bytes(benchmark::State& state, std::size_t bytes) {
  state.counters["bytes_per_second"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * static_cast<double>(bytes), benchmark::Counter::kIsRate);
}

std::vector<double> filled(std::size_t n, double v) {
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = v + 1e-9 * static_cast<double>(i % 1000);
  return a;
}

void BM_Read(benchmark::State& state) {
  const std::size_t n = doubles(state);
  const std::vector<double> a = filled(n, 1.0);
  for (auto _ : state) {
    // Four sums, so the loop is not one chain of dependent additions.
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    for (std::size_t i = 0; i + 4 <= n; i += 4) {
      s0 += a[i];
      s1 += a[i + 1];
      s2 += a[i + 2];
      s3 += a[i + 3];
    }
    benchmark::DoNotOptimize(s0 + s1 + s2 + s3);
  }
  count_bytes(state, n * sizeof(double));
}

void BM_Update(benchmark::State& state) {
  const std::size_t n = doubles(state);
  std::vector<double> a = filled(n, 1.0);
  const double c = 0.999999, d = 1e-9;
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) a[i] = a[i] * c + d;
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(a.data());
  count_bytes(state, 2 * n * sizeof(double));
}

void BM_Copy(benchmark::State& state) {
  const std::size_t n = doubles(state) / 2;  // two arrays: the argument is their sum
  const std::vector<double> a = filled(n, 1.0);
  std::vector<double> b(n, 0.0);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) b[i] = a[i];
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(b.data());
  count_bytes(state, 2 * n * sizeof(double));
}

void BM_Triad(benchmark::State& state) {
  const std::size_t n = doubles(state) / 3;  // three arrays: the argument is their sum
  std::vector<double> a(n, 0.0);
  const std::vector<double> b = filled(n, 1.0), d = filled(n, 2.0);
  const double c = 0.5;
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + c * d[i];
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(a.data());
  count_bytes(state, 3 * n * sizeof(double));
}

}  // namespace

BENCHMARK(BM_Read)->Arg(2)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Update)->Arg(2)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Copy)->Arg(2)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Triad)->Arg(2)->Arg(256)->Arg(512)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
