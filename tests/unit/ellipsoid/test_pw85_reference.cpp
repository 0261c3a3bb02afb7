// PW85 accuracy against the independent __float128 reference
// (pw85_reference.hpp) on hard classes, with the achieved relative error
// printed per class (copied into docs/pw85.md).
//
// What "accurate" means: the data are the doubles of Q1, Q2 and r. Changing
// each entry by one unit in the last place changes the exact mu^2 by a
// relative amount `sens` that we measure with the reference; for elongated
// bodies sens ~ eps * (aspect ratio)^2, because the small eigenvalue of a
// rotated needle's Q sits under the rounding of its large entries. No
// double-precision algorithm fed with those doubles can promise more. The
// deterministic first-order bound `cond` (componentwise condition number times
// eps, condition_bound below) is an upper estimate of that sensitivity; each
// case must satisfy err <= 4 cond + 4 eps (backward stability), and every
// class must also stay below a fixed ceiling.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>

#include "contact/ellipsoid/pw85.hpp"
#include "tests/unit/ellipsoid/pw85_reference.hpp"
#include "tests/unit/ellipsoid/random_ellipsoids.hpp"

namespace grains::contact {
namespace {

using Eigen::Vector3d;
using test::f128;
using test::Rng;

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Pair {
  Vector3d r;
  SymMat3 q1, q2;
};

// First-order bound on the relative change of mu^2 when every entry of Q1,
// Q2 and r is perturbed by at most one rounding (componentwise condition
// number times eps): with x = Q(l)^{-1} r, d mu^2 = l(1-l)(2 x.dr - x^T dQ(l) x).
double condition_bound(const Pair& p, double lambda, double mu2) {
  const double lc = 1 - lambda;
  const Mat3 Q = lc * to_matrix(p.q1) + lambda * to_matrix(p.q2);
  const Vector3d x = Q.ldlt().solve(p.r).cwiseAbs();
  const Mat3 absQ = lc * to_matrix(p.q1).cwiseAbs() + lambda * to_matrix(p.q2).cwiseAbs();
  return kEps * lambda * lc * (x.dot(absQ * x) + 2 * x.dot(p.r.cwiseAbs())) / mu2;
}

// Relative change of the exact mu^2 when every entry of Q1, Q2 and r moves by
// one ulp in a random direction (worst of two draws).
double sensitivity(const Pair& p, f128 ref, Rng& rng) {
  double s = 0;
  for (int draw = 0; draw < 2; ++draw) {
    Pair q = p;
    auto nudge = [&](double& v) { v = std::nextafter(v, rng.uniform() < 0.5 ? -INFINITY : INFINITY); };
    for (double& v : q.q1) nudge(v);
    for (double& v : q.q2) nudge(v);
    for (int i = 0; i < 3; ++i) nudge(q.r[i]);
    s = std::max(s, test::rel_err((double)test::pw85_reference(q.r, q.q1, q.q2).mu2, ref));
  }
  return s;
}

struct ClassReport {
  double worst_err = 0, worst_lambda = 0, worst_sens = 0, worst_ratio = 0, worst_cond_ratio = 0;
  int n = 0, iters = 0, max_iters = 0;
};

// Runs n cases from `make`, checks each against the reference and prints a line.
ClassReport run_class(const std::string& name, int n, std::uint64_t seed, double ceiling,
                      const std::function<Pair(Rng&)>& make) {
  Rng rng(seed);
  ClassReport c;
  for (int k = 0; k < n; ++k) {
    const Pair p = make(rng);
    const Pw85Result res = pw85_contact(p.r, p.q1, p.q2);
    EXPECT_EQ(res.status, Pw85Status::ok) << name << " case " << k;
    const test::Pw85Reference ref = test::pw85_reference(p.r, p.q1, p.q2);
    const double err = test::rel_err(res.mu2, ref.mu2);
    const double sens = sensitivity(p, ref.mu2, rng);
    const double cond = condition_bound(p, res.lambda, res.mu2);
    EXPECT_LE(err, 4 * cond + 4 * kEps) << name << " case " << k << ": mu2 " << res.mu2;
    c.worst_cond_ratio = std::max(c.worst_cond_ratio, err / cond);
    c.worst_err = std::max(c.worst_err, err);
    c.worst_sens = std::max(c.worst_sens, sens);
    c.worst_ratio = std::max(c.worst_ratio, err / (sens + kEps));
    const f128 lam_scale = ref.lambda < 0.5 ? ref.lambda : 1 - ref.lambda;
    const f128 dl = (f128)res.lambda - ref.lambda;
    c.worst_lambda = std::max(c.worst_lambda, (double)((dl < 0 ? -dl : dl) / lam_scale));
    c.iters += res.iterations;
    c.max_iters = std::max(c.max_iters, res.iterations);
    ++c.n;
  }
  std::printf("[pw85 accuracy] %-34s n=%4d  max rel err mu2 %8.2e  lambda %8.2e  |  1-ulp sensitivity %8.2e  "
              "err/sens %5.2f  err/cond %4.2f  |  evaluations mean %5.2f max %d\n",
              name.c_str(), c.n, c.worst_err, c.worst_lambda, c.worst_sens, c.worst_ratio, c.worst_cond_ratio,
              double(c.iters) / c.n, c.max_iters);
  EXPECT_LE(c.worst_err, ceiling) << name;
  return c;
}

// Two bodies with semi-axes `a1`, `a2` (before a random size factor in
// [0.02, 10] each, the range of the pw85 library's own test grid), random
// orientations, centre distance a fraction of the sum of their longest axes.
Pair random_pair(Rng& rng, Vector3d a1, Vector3d a2, double dmin = 0.05, double dmax = 1.2) {
  a1 *= rng.log_uniform(0.02, 10);
  a2 *= rng.log_uniform(0.02, 10);
  Pair p;
  p.q1 = quadratic_form(a1, rng.rotation());
  p.q2 = quadratic_form(a2, rng.rotation());
  p.r = rng.unit_vector() * (a1.maxCoeff() + a2.maxCoeff()) * rng.uniform(dmin, dmax);
  return p;
}

TEST(Pw85Reference, ProlateSpheroids) {
  const double ceiling[] = {1e-14, 1e-13, 5e-12, 5e-10};
  int i = 0;
  for (double ar : {2.0, 10.0, 100.0, 1000.0}) {
    run_class("prolate, aspect ratio " + std::to_string(int(ar)), 100, 100 + i, ceiling[i],
              [ar](Rng& rng) { return random_pair(rng, {ar, 1, 1}, {ar, 1, 1}); });
    ++i;
  }
}

TEST(Pw85Reference, OblateSpheroids) {
  const double ceiling[] = {1e-14, 1e-13, 5e-12, 1e-10};
  int i = 0;
  for (double ar : {2.0, 10.0, 100.0, 1000.0}) {
    run_class("oblate, aspect ratio " + std::to_string(int(ar)), 100, 200 + i, ceiling[i],
              [ar](Rng& rng) { return random_pair(rng, {ar, ar, 1}, {ar, ar, 1}); });
    ++i;
  }
}

TEST(Pw85Reference, TriaxialMixtures) {
  // A prolate-ish triaxial body against an oblate-ish one, axes up to ar : sqrt(ar) : 1.
  const double ceiling[] = {1e-14, 1e-13, 5e-12, 5e-10};
  int i = 0;
  for (double ar : {2.0, 10.0, 100.0, 1000.0}) {
    run_class("triaxial mixture, aspect ratio " + std::to_string(int(ar)), 100, 300 + i, ceiling[i],
              [ar](Rng& rng) {
                const double m = std::sqrt(ar);
                return random_pair(rng, {ar, m * rng.uniform(0.5, 1), 1}, {ar, ar / m * rng.uniform(1, 2), 1});
              });
    ++i;
  }
}

TEST(Pw85Reference, DeepOverlapsAndFarPairs) {
  run_class("deep overlap (|r| 1e-6..1e-2 of size)", 100, 400, 1e-13, [](Rng& rng) {
    Pair p = random_pair(rng, {5, 2, 1}, {3, 1, 1});
    p.r *= rng.log_uniform(1e-6, 1e-2);
    return p;
  });
  run_class("far pairs (|r| 1e2..1e6 of size)", 100, 401, 1e-13, [](Rng& rng) {
    Pair p = random_pair(rng, {5, 2, 1}, {3, 1, 1});
    p.r *= rng.log_uniform(1e2, 1e6);
    return p;
  });
}

TEST(Pw85Reference, SpheresOfVeryDifferentSizes) {
  run_class("sphere-like, radius ratio 1e3..1e6", 100, 500, 1e-14, [](Rng& rng) {
    const double big = rng.log_uniform(1e3, 1e6);
    Pair p;
    const double s1 = rng.uniform(0.999, 1.001), s2 = rng.uniform(0.999, 1.001);  // nearly round
    p.q1 = quadratic_form(Vector3d(big, big * s1, big / s2), rng.rotation());
    p.q2 = quadratic_form(Vector3d(1, s2, 1 / s1), rng.rotation());
    p.r = rng.unit_vector() * (big + 1) * rng.uniform(0.9, 1.1);
    return p;
  });
  run_class("small triaxial body next to a big one", 100, 501, 1e-12, [](Rng& rng) {
    const double big = rng.log_uniform(1e3, 1e6);
    Pair p;
    p.q1 = quadratic_form(Vector3d(2 * big, big, 1.5 * big), rng.rotation());
    p.q2 = quadratic_form(Vector3d(3, 1, 2), rng.rotation());
    p.r = rng.unit_vector() * big * rng.uniform(0.8, 2.5);
    return p;
  });
}

// Near-tangent pairs: a random pair rescaled (mu2(s r) = s^2 mu2(r)) so that
// its exact contact function is 1 +- eta. The overlap decision mu2 < 1 must be
// right whenever |mu2 - 1| exceeds what the data resolve (4 cond + 4 eps).
void near_tangent(const std::string& name, std::uint64_t seed, double ar, double ceiling) {
  Rng rng(seed);
  int decided = 0, unresolvable = 0;
  ClassReport c;
  for (int k = 0; k < 20; ++k) {
    const Pair base = random_pair(rng, {ar, std::sqrt(ar), 1}, {ar, 1, 1}, 0.3, 1.0);
    const f128 m2 = test::pw85_reference(base.r, base.q1, base.q2).mu2;
    for (double eta : {1e-3, 1e-6, 1e-9, 1e-11, 1e-13}) {
      for (double sign : {-1.0, 1.0}) {
        Pair p = base;
        const double scale = std::sqrt((double)((1 + (f128)sign * eta) / m2));
        p.r = base.r * scale;
        const test::Pw85Reference ref = test::pw85_reference(p.r, p.q1, p.q2);
        const Pw85Result res = pw85_contact(p.r, p.q1, p.q2);
        ASSERT_EQ(res.status, Pw85Status::ok);
        const double sens = sensitivity(p, ref.mu2, rng);
        const double err = test::rel_err(res.mu2, ref.mu2);
        c.worst_err = std::max(c.worst_err, err);
        c.worst_sens = std::max(c.worst_sens, sens);
        const f128 gap = ref.mu2 - 1;
        if ((double)(gap < 0 ? -gap : gap) > 4 * condition_bound(p, res.lambda, res.mu2) + 4 * kEps) {
          ++decided;
          EXPECT_EQ(res.mu2 < 1.0, ref.mu2 < 1) << name << " eta " << sign * eta << ": mu2 " << res.mu2;
        } else {
          ++unresolvable;
        }
      }
    }
  }
  std::printf("[pw85 accuracy] %-34s n=%4d  max rel err mu2 %8.2e  |  1-ulp sensitivity %8.2e  |  "
              "overlap decided %d, below data resolution %d\n",
              name.c_str(), decided + unresolvable, c.worst_err, c.worst_sens, decided, unresolvable);
  EXPECT_LE(c.worst_err, ceiling);
  EXPECT_GT(decided, 0);
}

TEST(Pw85Reference, NearTangentPairs) {
  near_tangent("near-tangent, aspect ratio 2", 600, 2, 1e-15);
  near_tangent("near-tangent, aspect ratio 10", 601, 10, 1e-14);
  near_tangent("near-tangent, aspect ratio 100", 602, 100, 5e-12);
  near_tangent("near-tangent, aspect ratio 1000", 603, 1000, 5e-10);
}

}  // namespace
}  // namespace grains::contact
