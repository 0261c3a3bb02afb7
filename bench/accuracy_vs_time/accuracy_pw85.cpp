// PW85 contact function: solver tolerance -> error of mu^2 and ns per
// evaluation, per aspect-ratio class, for cold starts, warm starts (lambda
// of the previous DEM step) and early exits on separated pairs. For the
// accuracy-vs-time report (bench/accuracy_vs_time/run.py); the pairs and
// the __float128 reference are those of bench/pw85 and the unit tests.
//
// Arguments: aspect ratio, k (tolerance 10^-k in u = log(lambda/(1-lambda))).
// Counters: mean and max relative error of mu^2 against the reference over
// 128 pairs (cold, warm), wrong decisions (early exit: a separated pair
// reported touching or the reverse; must be 0), f evaluations per call.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <vector>

#include "contact/ellipsoid/ellipsoid.hpp"
#include "contact/ellipsoid/pw85.hpp"
#include "tests/unit/ellipsoid/pw85_reference.hpp"
#include "tests/unit/ellipsoid/random_ellipsoids.hpp"

namespace {

using namespace grains::contact;
using Eigen::Vector3d;
using grains::test::Rng;

constexpr int kPairs = 1024;
constexpr int kChecked = 128;  // pairs compared with the (slow) reference

struct Pair {
  Vector3d r;
  SymMat3 q1, q2;
  double lambda_prev = -1;  // warm start (warm sets only)
  double mu2_ref = 0;       // reference mu^2 (first kChecked pairs)
};

Vector3d shape(Rng& rng, double ar, int kind) {
  switch (kind % 3) {
    case 0: return {ar, 1, 1};
    case 1: return {ar, ar, 1};
    default: return {ar, std::sqrt(ar) * rng.uniform(0.7, 1.0), 1};
  }
}

// Pairs with mu^2 uniform in [lo, hi]; with `warm`, each pair one DEM step
// later (bodies turned by 1e-3 rad, moved by 1e-3 of the small axis) and the
// previous step's lambda as the warm start.
const std::vector<Pair>& pairs(double ar, double lo, double hi, bool warm) {
  static std::map<std::tuple<double, double, bool>, std::vector<Pair>> cache;
  const auto key = std::make_tuple(ar, lo, warm);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  Rng rng(warm ? 2 : lo < 1 ? 1 : 4);
  std::vector<Pair> v;
  for (int k = 0; k < kPairs; ++k) {
    const Vector3d a1 = shape(rng, ar, k) * rng.log_uniform(0.5, 2), a2 = shape(rng, ar, k + 1) * rng.log_uniform(0.5, 2);
    Quat o1 = rng.rotation(), o2 = rng.rotation();
    Pair p;
    p.q1 = quadratic_form(a1, o1);
    p.q2 = quadratic_form(a2, o2);
    p.r = rng.unit_vector();
    p.r *= std::sqrt(rng.uniform(lo, hi) / pw85_contact(p.r, p.q1, p.q2).mu2);
    if (warm) {
      p.lambda_prev = pw85_contact(p.r, p.q1, p.q2).lambda;
      o1 = (o1 * Quat(Eigen::AngleAxisd(1e-3, rng.unit_vector()))).normalized();
      o2 = (o2 * Quat(Eigen::AngleAxisd(1e-3, rng.unit_vector()))).normalized();
      p.q1 = quadratic_form(a1, o1);
      p.q2 = quadratic_form(a2, o2);
      p.r += 1e-3 * a1.minCoeff() * rng.unit_vector();
    }
    if (k < kChecked) p.mu2_ref = static_cast<double>(grains::test::pw85_reference(p.r, p.q1, p.q2).mu2);
    v.push_back(p);
  }
  return cache.emplace(key, std::move(v)).first->second;
}

void errors(benchmark::State& state, const std::vector<Pair>& ps, const Pw85Options& base, bool warm) {
  double sum = 0, worst = 0;
  for (int k = 0; k < kChecked; ++k) {
    Pw85Options opt = base;
    if (warm) opt.lambda_guess = ps[k].lambda_prev;
    const double e = std::abs(pw85_contact(ps[k].r, ps[k].q1, ps[k].q2, opt).mu2 / ps[k].mu2_ref - 1.0);
    sum += e;
    worst = std::max(worst, e);
  }
  state.counters["mean_rel_err"] = sum / kChecked;
  state.counters["max_rel_err"] = worst;
}

void run(benchmark::State& state, bool warm) {
  const double ar = static_cast<double>(state.range(0));
  Pw85Options opt;
  opt.tolerance = std::pow(10.0, -static_cast<double>(state.range(1)));
  const auto& ps = pairs(ar, 0.5, 1.0, warm);
  errors(state, ps, opt, warm);
  long evals = 0, calls = 0;
  int i = 0;
  for (auto _ : state) {
    const Pair& p = ps[i];
    if (warm) opt.lambda_guess = p.lambda_prev;
    const Pw85Result res = pw85_contact(p.r, p.q1, p.q2, opt);
    benchmark::DoNotOptimize(res.mu2);
    evals += res.iterations;
    ++calls;
    i = (i + 1) & (kPairs - 1);
  }
  state.counters["evals"] = static_cast<double>(evals) / static_cast<double>(calls);
}

void BM_Cold(benchmark::State& state) { run(state, false); }
void BM_Warm(benchmark::State& state) { run(state, true); }

void BM_EarlyExit(benchmark::State& state) {
  // Separated neighbour pairs (mu^2 in [1.2, 4], inside a Verlet skin).
  const double ar = static_cast<double>(state.range(0));
  Pw85Options opt;
  opt.tolerance = std::pow(10.0, -static_cast<double>(state.range(1)));
  opt.stop_if_separated = true;
  const auto& ps = pairs(ar, 1.2, 4.0, false);
  long wrong = 0;
  for (const Pair& p : ps) {
    const Pw85Result res = pw85_contact(p.r, p.q1, p.q2, opt);
    if (res.status != Pw85Status::separated && !(res.status == Pw85Status::ok && res.mu2 > 1.0)) ++wrong;
  }
  long evals = 0, calls = 0;
  int i = 0;
  for (auto _ : state) {
    const Pair& p = ps[i];
    const Pw85Result res = pw85_contact(p.r, p.q1, p.q2, opt);
    benchmark::DoNotOptimize(res.mu2);
    evals += res.iterations;
    ++calls;
    i = (i + 1) & (kPairs - 1);
  }
  state.counters["evals"] = static_cast<double>(evals) / static_cast<double>(calls);
  state.counters["wrong_decisions"] = static_cast<double>(wrong);
}

void Args(benchmark::internal::Benchmark* b) {
  for (int ar : {1, 2, 10, 100, 1000})
    for (int k : {1, 2, 3, 4, 5, 7}) b->Args({ar, k});
}

BENCHMARK(BM_Cold)->Apply(Args);
BENCHMARK(BM_Warm)->Apply(Args);
BENCHMARK(BM_EarlyExit)->Apply(Args);

}  // namespace

BENCHMARK_MAIN();
