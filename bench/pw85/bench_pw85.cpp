// ns per PW85 contact-function evaluation for the aspect ratios of issue 3
// (1, 2, 10, 100, 1000): cold solves, warm starts from the previous step's
// lambda, early exits on separated pairs, and the full DEM contact geometry.
// Each benchmark cycles through 1024 random pairs (random orientations, prolate
// and oblate spheroids and triaxial bodies mixed), and reports the mean number
// of f evaluations and, for the cold solve, the worst relative error of mu^2
// against the __float128 reference of the tests.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "contact/ellipsoid/ellipsoid_contact.hpp"
#include "contact/ellipsoid/point_ellipsoid.hpp"
#include "contact/ellipsoid/pw85.hpp"
#include "contact/ellipsoid/pw85_lanes.hpp"
#include "tests/unit/ellipsoid/pw85_reference.hpp"
#include "tests/unit/ellipsoid/random_ellipsoids.hpp"

namespace {

using namespace grains::contact;
using Eigen::Vector3d;
using grains::test::Rng;

constexpr int kPairs = 1024;

struct Pair {
  Vector3d r;
  SymMat3 q1, q2;
  Vector3d a1, a2;
  Quat o1, o2;
};

Vector3d shape(Rng& rng, double ar, int kind) {
  switch (kind % 3) {
    case 0: return {ar, 1, 1};                   // prolate
    case 1: return {ar, ar, 1};                  // oblate
    default: return {ar, std::sqrt(ar) * rng.uniform(0.7, 1.0), 1};  // triaxial
  }
}

// Pairs with mu^2 uniform in [lo, hi]: random pose, then r rescaled
// (mu^2(s r) = s^2 mu^2(r)).
std::vector<Pair> make_pairs(double ar, double lo, double hi, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Pair> v;
  for (int k = 0; k < kPairs; ++k) {
    Pair p;
    p.a1 = shape(rng, ar, k) * rng.log_uniform(0.5, 2);
    p.a2 = shape(rng, ar, k + 1) * rng.log_uniform(0.5, 2);
    p.o1 = rng.rotation();
    p.o2 = rng.rotation();
    p.q1 = quadratic_form(p.a1, p.o1);
    p.q2 = quadratic_form(p.a2, p.o2);
    p.r = rng.unit_vector();
    const double m2 = pw85_contact(p.r, p.q1, p.q2).mu2;
    p.r *= std::sqrt(rng.uniform(lo, hi) / m2);
    v.push_back(p);
  }
  return v;
}

// Cold solves of the 1024 pairs of the class with the given options, and the
// worst relative error of mu^2 against the reference at the same options (on
// a subset: the reference is slow), so speed and accuracy come together.
void run_cold(benchmark::State& state, const Pw85Options& opt) {
  const double ar = state.range(0);
  const std::vector<Pair> pairs = make_pairs(ar, 0.5, 1.0, 1);
  double worst = 0;
  for (int k = 0; k < kPairs; k += 8) {
    const Pw85Result res = pw85_contact(pairs[k].r, pairs[k].q1, pairs[k].q2, opt);
    worst = std::max(worst, grains::test::rel_err(res.mu2, grains::test::pw85_reference(pairs[k].r, pairs[k].q1, pairs[k].q2).mu2));
  }
  long evals = 0, calls = 0;
  int i = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i];
    const Pw85Result res = pw85_contact(p.r, p.q1, p.q2, opt);
    benchmark::DoNotOptimize(res.mu2);
    evals += res.iterations;
    ++calls;
    i = (i + 1) & (kPairs - 1);
  }
  state.counters["evals"] = double(evals) / calls;
  state.counters["max_rel_err"] = worst;
}

// The public default: input checked, full double precision.
void BM_Cold(benchmark::State& state) { run_cold(state, Pw85Options{}); }

// range(1) = 1 for trusted input (no input checks, as the DEM calls it),
// range(2) = -log10 of the Newton tolerance in u (default 7).
void BM_ColdOptions(benchmark::State& state) {
  Pw85Options opt;
  opt.trusted_input = state.range(1) == 1;
  opt.tolerance = std::pow(10.0, -static_cast<double>(state.range(2)));
  run_cold(state, opt);
}

void BM_Warm(benchmark::State& state) {
  // The same pairs one DEM step later: each body turned by 1e-3 rad and moved
  // by 1e-3 of its size; lambda from the previous step.
  const double ar = state.range(0);
  std::vector<Pair> pairs = make_pairs(ar, 0.5, 1.0, 2);
  std::vector<double> lambda(kPairs);
  Rng rng(3);
  for (int k = 0; k < kPairs; ++k) {
    Pair& p = pairs[k];
    lambda[k] = pw85_contact(p.r, p.q1, p.q2).lambda;
    p.q1 = quadratic_form(p.a1, (p.o1 * Quat(Eigen::AngleAxisd(1e-3, rng.unit_vector()))).normalized());
    p.q2 = quadratic_form(p.a2, (p.o2 * Quat(Eigen::AngleAxisd(1e-3, rng.unit_vector()))).normalized());
    p.r += 1e-3 * p.a1.minCoeff() * rng.unit_vector();
  }
  long evals = 0, calls = 0;
  int i = 0;
  Pw85Options opt;
  for (auto _ : state) {
    const Pair& p = pairs[i];
    opt.lambda_guess = lambda[i];
    const Pw85Result res = pw85_contact(p.r, p.q1, p.q2, opt);
    benchmark::DoNotOptimize(res.mu2);
    evals += res.iterations;
    ++calls;
    i = (i + 1) & (kPairs - 1);
  }
  state.counters["evals"] = double(evals) / calls;
}

void BM_EarlyExit(benchmark::State& state) {
  // Separated neighbour pairs (mu^2 in [1.2, 4], inside a Verlet skin).
  const double ar = state.range(0);
  const std::vector<Pair> pairs = make_pairs(ar, 1.2, 4.0, 4);
  long evals = 0, calls = 0, decided = 0;
  int i = 0;
  Pw85Options opt;
  opt.stop_if_separated = true;
  for (auto _ : state) {
    const Pair& p = pairs[i];
    const Pw85Result res = pw85_contact(p.r, p.q1, p.q2, opt);
    benchmark::DoNotOptimize(res.mu2);
    evals += res.iterations;
    decided += res.status == Pw85Status::separated;
    ++calls;
    i = (i + 1) & (kPairs - 1);
  }
  state.counters["evals"] = double(evals) / calls;
  state.counters["separated"] = double(decided) / calls;
}

void BM_DemContact(benchmark::State& state) {
  // What a DEM force loop calls per touching pair: PW85 (warm) + geometry
  // (support points, overlap, both curvature tensors, R*).
  const double ar = state.range(0);
  const std::vector<Pair> pairs = make_pairs(ar, 0.5, 1.0, 5);
  std::vector<double> lambda(kPairs);
  for (int k = 0; k < kPairs; ++k) lambda[k] = pw85_contact(pairs[k].r, pairs[k].q1, pairs[k].q2).lambda;
  int i = 0;
  const Vector3d origin = Vector3d::Zero();
  for (auto _ : state) {
    const Pair& p = pairs[i];
    const EllipsoidPairContact c = ellipsoid_contact(origin, p.q1, p.r, p.q2, lambda[i]);
    benchmark::DoNotOptimize(c.geometry.overlap);
    i = (i + 1) & (kPairs - 1);
  }
}

// The same work for a whole list of touching pairs, kLanes pairs in lockstep
// (pw85_lanes.hpp, what the DEM's pair stage runs): PW85 (warm) + geometry.
// Time per pair.
void BM_DemContactLanes(benchmark::State& state) {
  const double ar = state.range(0);
  const std::vector<Pair> pairs = make_pairs(ar, 0.5, 1.0, 5);
  std::vector<Pw85LaneJob> jobs(kPairs);
  std::vector<Pw85LaneResult> res(kPairs);
  std::vector<PairGeometryJob> gjobs(kPairs);
  std::vector<ContactGeometry> geo(kPairs);
  const Vector3d origin = Vector3d::Zero();
  for (int k = 0; k < kPairs; ++k) {
    const double lambda = pw85_contact(pairs[k].r, pairs[k].q1, pairs[k].q2).lambda;
    jobs[k] = {pairs[k].q1.data(), pairs[k].q2.data(), {pairs[k].r[0], pairs[k].r[1], pairs[k].r[2]}, lambda};
  }
  for (auto _ : state) {
    pw85_contact_lanes(jobs.data(), kPairs, res.data(), 1e-4, true);
    for (int k = 0; k < kPairs; ++k)
      gjobs[k] = {origin.data(), pairs[k].q1.data(), pairs[k].r.data(), pairs[k].q2.data(),
                  {res[k].x[0], res[k].x[1], res[k].x[2]}};
    contact_geometry_lanes(gjobs.data(), kPairs, geo.data());
    benchmark::DoNotOptimize(geo.data());
  }
  state.SetItemsProcessed(state.iterations() * kPairs);
  state.counters["ns_per_pair"] = benchmark::Counter(static_cast<double>(state.iterations()) * kPairs,
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_SphereEllipsoid(benchmark::State& state) {
  const double ar = state.range(0);
  Rng rng(6);
  std::vector<Ellipsoid> bodies(kPairs);
  std::vector<Vector3d> centres(kPairs);
  for (int k = 0; k < kPairs; ++k) {
    bodies[k].semi_axes = shape(rng, ar, k);
    bodies[k].orientation = rng.rotation();
    centres[k] = rng.unit_vector() * ar * rng.uniform(0.5, 1.2);
  }
  int i = 0;
  for (auto _ : state) {
    const ContactGeometry g = sphere_ellipsoid_contact(centres[i], 0.5, bodies[i]);
    benchmark::DoNotOptimize(g.overlap);
    i = (i + 1) & (kPairs - 1);
  }
}

#define ASPECT_RATIOS Arg(1)->Arg(2)->Arg(10)->Arg(100)->Arg(1000)
BENCHMARK(BM_Cold)->ASPECT_RATIOS;
BENCHMARK(BM_ColdOptions)->ArgsProduct({{1, 2, 10, 100, 1000}, {0, 1}, {7, 4, 3}});
BENCHMARK(BM_Warm)->ASPECT_RATIOS;
BENCHMARK(BM_EarlyExit)->ASPECT_RATIOS;
BENCHMARK(BM_DemContact)->ASPECT_RATIOS;
BENCHMARK(BM_DemContactLanes)->ASPECT_RATIOS;
BENCHMARK(BM_SphereEllipsoid)->ASPECT_RATIOS;

}  // namespace

BENCHMARK_MAIN();
