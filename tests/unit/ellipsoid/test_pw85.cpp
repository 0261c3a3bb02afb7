// PW85 contact function: exact properties (spheres, symmetry, invariance,
// scaling, analytic tangency), warm start, early exit, and error reporting.
// Accuracy against high-precision references: test_pw85_reference.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "contact/ellipsoid/pw85.hpp"
#include "tests/unit/ellipsoid/pw85_reference.hpp"
#include "tests/unit/ellipsoid/random_ellipsoids.hpp"

namespace grains::contact {
namespace {

using Eigen::Vector3d;
using test::f128;
using test::Rng;

constexpr double kEps = std::numeric_limits<double>::epsilon();

SymMat3 sphere(double a) { return {a * a, 0, 0, a * a, 0, a * a}; }

// A random triaxial body with aspect ratio up to `ar` and size around `size`.
SymMat3 random_body(Rng& rng, double ar, double size = 1.0) {
  const Vector3d a(size * rng.log_uniform(1.0, ar), size, size / rng.log_uniform(1.0, ar));
  return quadratic_form(a, rng.rotation());
}

TEST(Pw85, SpheresAreExact) {
  // mu = |r| / (a1 + a2), lambda = a1 / (a1 + a2): compared with the exact
  // values of the double data, computed in __float128.
  Rng rng(1);
  double worst_mu = 0, worst_lambda = 0;
  for (int k = 0; k < 2000; ++k) {
    const double a1 = rng.log_uniform(1e-3, 1e3), a2 = rng.log_uniform(1e-3, 1e3);
    const Vector3d r = rng.unit_vector() * (a1 + a2) * rng.log_uniform(1e-3, 1e3);
    const Pw85Result res = pw85_contact(r, sphere(a1), sphere(a2));
    ASSERT_EQ(res.status, Pw85Status::ok);
    // The solver sees Q = fl(a^2); the exact answer for those data is
    // |r|^2 / (sqrt(Q1) + sqrt(Q2))^2, which agrees with a to within eps.
    const f128 rr = (f128)r[0] * r[0] + (f128)r[1] * r[1] + (f128)r[2] * r[2];
    const f128 s = (f128)a1 + (f128)a2;
    worst_mu = std::max(worst_mu, test::rel_err(res.mu2, rr / (s * s)));
    worst_lambda = std::max(worst_lambda, test::rel_err(res.lambda, (f128)a1 / s));
    EXPECT_EQ(res.iterations, 1) << "the cold start is exact for spheres";
    EXPECT_NEAR(res.normal.dot(r.normalized()), 1.0, 4 * kEps);
    // x0 lies at distance mu a1 from c1 along r.
    EXPECT_NEAR(res.x0_rel.norm(), std::sqrt(res.mu2) * a1, 1e-14 * std::sqrt(res.mu2) * a1);
  }
  std::cout << "spheres: worst relative error mu2 " << worst_mu << ", lambda " << worst_lambda << "\n";
  EXPECT_LT(worst_mu, 8 * kEps);
  EXPECT_LT(worst_lambda, 8 * kEps);
}

TEST(Pw85, MaximumDominatesEveryF) {
  // mu2 = max f: no f(lambda) on a grid may exceed it (beyond rounding) and
  // the reported lambda attains it.
  Rng rng(2);
  for (int k = 0; k < 200; ++k) {
    const SymMat3 q1 = random_body(rng, 20), q2 = random_body(rng, 20, rng.log_uniform(0.1, 10));
    const Vector3d r = rng.unit_vector() * rng.uniform(0.1, 30);
    const Pw85Result res = pw85_contact(r, q1, q2);
    ASSERT_EQ(res.status, Pw85Status::ok);
    // Both sides carry the evaluation error ~ eps * cond(Q) (cond <= 400 here).
    for (int i = 1; i < 100; ++i) EXPECT_LE(pw85_f(i / 100.0, r, q1, q2), res.mu2 * (1 + 2e-12));
    EXPECT_NEAR(pw85_f(res.lambda, r, q1, q2), res.mu2, 2e-12 * res.mu2);
  }
}

TEST(Pw85, SwapGivesSameMuAndComplementaryLambda) {
  Rng rng(3);
  double worst = 0;
  for (int k = 0; k < 500; ++k) {
    const SymMat3 q1 = random_body(rng, 10), q2 = random_body(rng, 10, rng.log_uniform(0.2, 5));
    const Vector3d r = rng.unit_vector() * rng.uniform(0.1, 10);
    const Pw85Result a = pw85_contact(r, q1, q2), b = pw85_contact(-r, q2, q1);
    ASSERT_EQ(a.status, Pw85Status::ok);
    ASSERT_EQ(b.status, Pw85Status::ok);
    worst = std::max(worst, std::abs(a.mu2 - b.mu2) / a.mu2);
    EXPECT_NEAR(b.lambda, 1.0 - a.lambda, 1e-12);
    EXPECT_NEAR(a.normal.dot(-b.normal), 1.0, 1e-12);  // both point from the body passed first
    // The tangency point x0 is the same point of space.
    EXPECT_LT((a.x0_rel - (r + b.x0_rel)).norm(), 1e-12 * r.norm());
  }
  std::cout << "swap: worst relative mu2 difference " << worst << "\n";
  EXPECT_LT(worst, 1e-13);
}

TEST(Pw85, RotationInvariance) {
  Rng rng(4);
  double worst = 0;
  for (int k = 0; k < 500; ++k) {
    const Vector3d a1(rng.uniform(0.5, 5), rng.uniform(0.5, 5), rng.uniform(0.5, 5));
    const Vector3d a2(rng.uniform(0.5, 5), rng.uniform(0.5, 5), rng.uniform(0.5, 5));
    const Quat o1 = rng.rotation(), o2 = rng.rotation(), g = rng.rotation();
    const Vector3d r = rng.unit_vector() * rng.uniform(0.5, 15);
    const Pw85Result a = pw85_contact(r, quadratic_form(a1, o1), quadratic_form(a2, o2));
    const Pw85Result b = pw85_contact(g * r, quadratic_form(a1, g * o1), quadratic_form(a2, g * o2));
    ASSERT_EQ(a.status, Pw85Status::ok);
    ASSERT_EQ(b.status, Pw85Status::ok);
    worst = std::max(worst, std::abs(a.mu2 - b.mu2) / a.mu2);
    EXPECT_NEAR(b.lambda, a.lambda, 1e-12);
    EXPECT_NEAR((g * a.normal).dot(b.normal), 1.0, 1e-12);
  }
  std::cout << "rotation: worst relative mu2 difference " << worst << "\n";
  // Rotating Q rounds its entries: the difference is the data's, not the solver's.
  EXPECT_LT(worst, 1e-13);
}

TEST(Pw85, ScalingOfR) {
  // mu2(s r) = s^2 mu2(r): bit-exact for powers of two, to rounding otherwise.
  Rng rng(5);
  for (int k = 0; k < 300; ++k) {
    const SymMat3 q1 = random_body(rng, 30), q2 = random_body(rng, 30);
    const Vector3d r = rng.unit_vector() * rng.uniform(0.1, 10);
    const Pw85Result a = pw85_contact(r, q1, q2);
    for (double s : {0.25, 2.0, 1024.0, 0x1p-40}) {
      const Pw85Result b = pw85_contact(s * r, q1, q2);
      EXPECT_EQ(b.mu2, s * s * a.mu2);
      EXPECT_EQ(b.lambda, a.lambda);
    }
    const double s = rng.uniform(0.01, 100);
    const Pw85Result b = pw85_contact(s * r, q1, q2);
    EXPECT_NEAR(b.mu2, s * s * a.mu2, 1e-12 * s * s * a.mu2);  // s r is rounded
  }
}

TEST(Pw85, TinyAndHugeScales) {
  // The whole configuration scaled by L (Q by L^2, r by L) leaves mu2 and lambda
  // unchanged, down to lengths of 1e-150 and up to 1e150 (Q ~ 1e+-300), where
  // a naive evaluation of r^T Q^{-1} r would over- or underflow.
  Rng rng(6);
  for (int k = 0; k < 100; ++k) {
    const SymMat3 q1 = random_body(rng, 10), q2 = random_body(rng, 10);
    const Vector3d r = rng.unit_vector() * rng.uniform(0.1, 8);
    const Pw85Result a = pw85_contact(r, q1, q2);
    for (double L : {0x1p-500, 0x1p-200, 0x1p300, 0x1p500, 1e-150, 3e-77, 7e88, 1e150}) {
      SymMat3 p1 = q1, p2 = q2;
      for (int i = 0; i < 6; ++i) {
        p1[i] *= L * L;
        p2[i] *= L * L;
      }
      const Pw85Result b = pw85_contact(L * r, p1, p2);
      ASSERT_EQ(b.status, Pw85Status::ok) << "L = " << L;
      EXPECT_NEAR(b.mu2, a.mu2, 1e-13 * a.mu2) << "L = " << L;
      EXPECT_NEAR(b.lambda, a.lambda, 1e-12) << "L = " << L;
      EXPECT_NEAR((b.x0_rel / L - a.x0_rel).norm(), 0.0, 1e-12 * a.x0_rel.norm()) << "L = " << L;
    }
    // r alone far beyond the bodies' size or deep inside: mu2 = s^2 mu2(r).
    for (double s : {1e-140, 1e120}) {
      const Pw85Result b = pw85_contact(s * r, q1, q2);
      ASSERT_EQ(b.status, Pw85Status::ok);
      EXPECT_NEAR(b.mu2 / (s * s), a.mu2, 1e-13 * a.mu2) << "s = " << s;
    }
  }
}

TEST(Pw85, AnalyticTangentConfigurations) {
  // Externally tangent by symmetry, so mu2 = 1 up to the rounding of the data.
  for (double ar : {1.0, 1.5, 2.0, 10.0, 100.0, 1000.0}) {
    const double a = 0.7 * ar, b = 0.7;  // prolate along x: semi-axes (a, b, b)
    const double a2 = 1.3 * ar, b2 = 1.3;
    const Mat3 I = Mat3::Identity();
    Mat3 Rz;  // x -> y
    Rz << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    const SymMat3 px = quadratic_form(Vector3d(a, b, b), I);
    const SymMat3 px2 = quadratic_form(Vector3d(a2, b2, b2), I);
    const SymMat3 py2 = quadratic_form(Vector3d(a2, b2, b2), Rz);
    const SymMat3 ox = quadratic_form(Vector3d(b, a, a), I);  // oblate, axis x
    struct Case {
      const char* what;
      Vector3d r;
      SymMat3 q1, q2;
    } cases[] = {
        {"tip to tip", {a + a2, 0, 0}, px, px2},
        {"side by side", {0, b + b2, 0}, px, px2},
        {"crossed, along z", {0, 0, b + b2}, px, py2},
        {"crossed, tip on flank", {a + b2, 0, 0}, px, py2},
        {"oblate face to prolate tip", {b + a2, 0, 0}, ox, px2},
        {"oblate rim to prolate flank", {0, a + b2, 0}, ox, px2},
    };
    for (const Case& c : cases) {
      const Pw85Result res = pw85_contact(c.r, c.q1, c.q2);
      ASSERT_EQ(res.status, Pw85Status::ok);
      EXPECT_NEAR(res.mu2, 1.0, 8 * kEps) << c.what << ", aspect ratio " << ar;
      EXPECT_NEAR(std::abs(res.normal.dot(c.r.normalized())), 1.0, 1e-15) << c.what;
    }
  }
}

TEST(Pw85, CoincidentCentresAndDeepOverlap) {
  Rng rng(7);
  const SymMat3 q1 = random_body(rng, 10), q2 = random_body(rng, 10);
  const Pw85Result z = pw85_contact(Vector3d::Zero(), q1, q2);
  EXPECT_EQ(z.status, Pw85Status::ok);
  EXPECT_EQ(z.mu2, 0.0);
  EXPECT_EQ(z.lambda, 0.5);
  EXPECT_TRUE(z.normal.allFinite());
  for (double s : {1e-3, 1e-8, 1e-15, 1e-30, 1e-100, 1e-150}) {
    const Vector3d r = rng.unit_vector() * s;
    const Pw85Result res = pw85_contact(r, q1, q2);
    ASSERT_EQ(res.status, Pw85Status::ok) << s;
    const test::Pw85Reference ref = test::pw85_reference(r, q1, q2);
    EXPECT_LT(test::rel_err(res.mu2, ref.mu2), 1e-13) << s;
    EXPECT_TRUE(res.x0_rel.allFinite() && res.normal.allFinite());
  }
}

TEST(Pw85, WarmStartConvergesInFewIterations) {
  // A persistent contact: the bodies move and turn a little each step; the
  // previous lambda makes the solve one or two evaluations.
  Rng rng(8);
  int cold_total = 0, warm_total = 0;
  for (int k = 0; k < 200; ++k) {
    const Vector3d a1(3, 1, 0.5), a2(2, 1.5, 0.7);
    Quat o1 = rng.rotation(), o2 = rng.rotation();
    Vector3d r = rng.unit_vector() * 3.0;
    double lambda = -1;
    for (int step = 0; step < 20; ++step) {
      const SymMat3 q1 = quadratic_form(a1, o1), q2 = quadratic_form(a2, o2);
      Pw85Options warm;
      warm.lambda_guess = lambda;
      const Pw85Result w = pw85_contact(r, q1, q2, warm);
      const Pw85Result c = pw85_contact(r, q1, q2);
      ASSERT_EQ(w.status, Pw85Status::ok);
      EXPECT_NEAR(w.mu2, c.mu2, 1e-14 * c.mu2);
      EXPECT_NEAR(w.lambda, c.lambda, 1e-12);
      if (step > 0) {
        cold_total += c.iterations;
        warm_total += w.iterations;
        EXPECT_LE(w.iterations, 3);
      }
      lambda = w.lambda;
      o1 = (o1 * Quat(Eigen::AngleAxisd(1e-3, rng.unit_vector()))).normalized();
      o2 = (o2 * Quat(Eigen::AngleAxisd(1e-3, rng.unit_vector()))).normalized();
      r += 1e-3 * rng.unit_vector();
    }
  }
  std::cout << "warm start: mean evaluations " << warm_total / (200.0 * 19) << " (cold "
            << cold_total / (200.0 * 19) << ")\n";
  EXPECT_LT(warm_total, cold_total);
}

TEST(Pw85, EarlyExitProvesSeparation) {
  Rng rng(9);
  int n = 0, one_eval = 0;
  for (int k = 0; k < 500; ++k) {
    const SymMat3 q1 = random_body(rng, 10), q2 = random_body(rng, 10);
    const Vector3d r = rng.unit_vector() * rng.uniform(0.1, 40);
    Pw85Options opt;
    opt.stop_if_separated = true;
    const Pw85Result fast = pw85_contact(r, q1, q2, opt);
    const Pw85Result full = pw85_contact(r, q1, q2);
    ASSERT_EQ(full.status, Pw85Status::ok);
    if (full.mu2 < 1.0) {
      // Overlapping pairs can never be reported separated.
      EXPECT_EQ(fast.status, Pw85Status::ok);
      EXPECT_EQ(fast.mu2, full.mu2);
    } else if (fast.status == Pw85Status::separated) {
      ++n;
      one_eval += fast.iterations == 1;
      EXPECT_GT(fast.mu2, 1.0);
      EXPECT_LE(fast.mu2, full.mu2 * (1 + 1e-15));
      EXPECT_LE(fast.iterations, full.iterations);
    }
  }
  std::cout << "early exit: " << n << " separated pairs, " << one_eval << " decided by one evaluation\n";
  EXPECT_GT(n, 100);
}

TEST(Pw85, InvalidInputIsReported) {
  const SymMat3 good = sphere(1.0);
  const Vector3d r(1, 2, 3);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  SymMat3 with_nan = good, with_inf = good;
  with_nan[4] = nan;
  with_inf[0] = inf;
  EXPECT_EQ(pw85_contact(r, with_nan, good).status, Pw85Status::non_finite_input);
  EXPECT_EQ(pw85_contact(r, good, with_inf).status, Pw85Status::non_finite_input);
  EXPECT_EQ(pw85_contact(Vector3d(nan, 0, 0), good, good).status, Pw85Status::non_finite_input);
  EXPECT_EQ(pw85_contact(Vector3d(0, -inf, 0), good, good).status, Pw85Status::non_finite_input);

  const SymMat3 zero{0, 0, 0, 0, 0, 0};
  const SymMat3 negative{-1, 0, 0, 1, 0, 1};
  const SymMat3 indefinite{1, 2, 0, 1, 0, 1};  // eigenvalues -1, 1, 3
  const SymMat3 singular{1, 1, 0, 1, 0, 1};    // rank 2
  for (const SymMat3& bad : {zero, negative, indefinite, singular}) {
    const Pw85Result a = pw85_contact(r, bad, good), b = pw85_contact(r, good, bad);
    EXPECT_EQ(a.status, Pw85Status::not_spd);
    EXPECT_EQ(b.status, Pw85Status::not_spd);
    EXPECT_FALSE(is_spd(bad));
  }
  EXPECT_TRUE(is_spd(good));
  EXPECT_STREQ(to_string(Pw85Status::not_spd), "not symmetric positive-definite");
}

TEST(Pw85, NoNaNUpToAspectRatioOneMillion) {
  // Needles and pancakes up to 1e6 : 1 in every orientation and distance:
  // the solver must converge to a finite value (accuracy is limited by the
  // conditioning, see test_pw85_reference.cpp).
  Rng rng(10);
  int count = 0;
  double worst = 0;
  for (double ar : {1e4, 1e5, 1e6}) {
    for (int k = 0; k < 300; ++k) {
      const int kind = k % 3;
      const Vector3d a = kind == 0 ? Vector3d(ar, 1, 1) : kind == 1 ? Vector3d(1, ar, ar) : Vector3d(ar, std::sqrt(ar), 1);
      const SymMat3 q1 = quadratic_form(a * rng.log_uniform(0.1, 10), rng.rotation());
      const SymMat3 q2 = quadratic_form(a * rng.log_uniform(0.1, 10), rng.rotation());
      const Vector3d r = rng.unit_vector() * ar * rng.log_uniform(1e-3, 30);
      const Pw85Result res = pw85_contact(r, q1, q2);
      ASSERT_EQ(res.status, Pw85Status::ok) << "aspect ratio " << ar << ", case " << k;
      ASSERT_TRUE(std::isfinite(res.mu2) && res.mu2 > 0.0);
      ASSERT_TRUE(std::isfinite(res.lambda) && res.lambda > 0.0 && res.lambda < 1.0);
      ASSERT_TRUE(res.normal.allFinite() && res.x0_rel.allFinite());
      ASSERT_LE(res.iterations, 60);
      if (k % 10 == 0) worst = std::max(worst, test::rel_err(res.mu2, test::pw85_reference(r, q1, q2).mu2));
      ++count;
    }
  }
  std::cout << count << " pairs with aspect ratio 1e4..1e6: no NaN; worst sampled relative error " << worst
            << "\n";
}

}  // namespace
}  // namespace grains::contact
