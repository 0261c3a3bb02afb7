// The lockstep PW85 and geometry (pw85_lanes.hpp) give each pair the result
// of the scalar functions: same status, mu2, lambda and geometry, over
// aspect ratios 1..1000, overlapping and separated pairs, warm and cold
// starts, coincident centres, and list lengths that do not fill the last
// group of lanes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "contact/ellipsoid/ellipsoid_contact.hpp"
#include "contact/ellipsoid/pw85_lanes.hpp"
#include "tests/unit/ellipsoid/random_ellipsoids.hpp"

namespace grains::contact {
namespace {

using Eigen::Vector3d;
using test::Rng;

struct Body {
  Vector3d c;
  SymMat3 q;
};

// Same value to a few units in the last place (the lanes and the scalar
// code run the same operations; only a build that contracts a*b+c into FMAs
// differently in packed and scalar code could differ at all).
void expect_close(double got, double want, double scale, const char* what, std::size_t k) {
  EXPECT_LE(std::abs(got - want), 1e-13 * std::max(std::abs(want), scale)) << what << " of pair " << k;
}

void check_list(Rng& rng, std::size_t count, bool stop_if_separated) {
  std::vector<Body> a(count), b(count);
  std::vector<Pw85LaneJob> jobs(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double ar = rng.log_uniform(1.0, 1000.0);
    const int kind = static_cast<int>(rng.uniform() * 3);
    auto axes = [&] {
      const double s = rng.log_uniform(0.5, 2.0);
      if (kind == 0) return Vector3d(s * ar, s, s);                       // prolate
      if (kind == 1) return Vector3d(s, s, s / ar);                       // oblate
      return Vector3d(s * ar, s * std::sqrt(ar) * rng.uniform(0.3, 1), s);  // triaxial
    };
    const Vector3d ai = axes(), aj = axes();
    a[k] = {Vector3d(rng.normal(), rng.normal(), rng.normal()), quadratic_form(ai, rng.rotation())};
    const double reach = ai.maxCoeff() + aj.maxCoeff();
    Vector3d r = rng.unit_vector() * reach * rng.uniform(0.01, 1.2);
    if (k % 97 == 5) r.setZero();  // coincident centres
    b[k] = {a[k].c + r, quadratic_form(aj, rng.rotation())};
    const double u = rng.uniform();
    jobs[k] = {a[k].q.data(), b[k].q.data(), {r[0], r[1], r[2]}, u < 0.3 ? -1.0 : (u < 0.4 ? 1e-9 : u)};
    if (u > 0.95) jobs[k].lambda_guess = 1.0 - 1e-12;
  }
  std::vector<Pw85LaneResult> res(count);
  pw85_contact_lanes(jobs.data(), count, res.data(), 1e-4, stop_if_separated);

  std::vector<PairGeometryJob> gj;
  std::vector<ContactGeometry> want_g;
  std::size_t touching = 0, separated = 0;
  for (std::size_t k = 0; k < count; ++k) {
    Pw85Options opt;
    opt.lambda_guess = jobs[k].lambda_guess;
    opt.stop_if_separated = stop_if_separated;
    opt.trusted_input = true;
    opt.tolerance = 1e-4;
    const Vector3d r(jobs[k].r[0], jobs[k].r[1], jobs[k].r[2]);
    const Pw85Result want = pw85_contact(r, a[k].q, b[k].q, opt);
    ASSERT_EQ(static_cast<int>(res[k].status), static_cast<int>(want.status)) << "pair " << k;
    expect_close(res[k].mu2, want.mu2, 0.0, "mu2", k);
    expect_close(res[k].lambda, want.lambda, 0.0, "lambda", k);
    separated += want.status == Pw85Status::separated;
    if (want.status != Pw85Status::ok) continue;
    ++touching;
    if (!r.isZero()) {
      const Vector3d x(res[k].x[0], res[k].x[1], res[k].x[2]);
      EXPECT_LE((x.normalized() - want.normal).norm(), 1e-13) << "normal of pair " << k;
    }
    gj.push_back({a[k].c.data(), a[k].q.data(), b[k].c.data(), b[k].q.data(), {res[k].x[0], res[k].x[1], res[k].x[2]}});
    want_g.push_back(contact_geometry_from_pw85(a[k].c, a[k].q, b[k].c, b[k].q, want));
  }
  std::vector<ContactGeometry> got_g(gj.size());
  contact_geometry_lanes(gj.data(), gj.size(), got_g.data());
  for (std::size_t k = 0; k < gj.size(); ++k) {
    const ContactGeometry &g = got_g[k], &w = want_g[k];
    const double scale = std::sqrt(std::max({w.point.squaredNorm(), 1.0}));
    expect_close(g.overlap, w.overlap, 1e-3 * scale, "overlap", k);
    expect_close(g.radius, w.radius, 0.0, "R*", k);
    EXPECT_LE((g.normal - w.normal).norm(), 1e-13) << "normal of geometry " << k;
    EXPECT_LE((g.point - w.point).norm(), 1e-13 * scale) << "point of geometry " << k;
  }
  if (count > 100) {
    // The classes the comparison must have covered.
    EXPECT_GT(touching, count / 10);
    if (stop_if_separated) {
      EXPECT_GT(separated, count / 10);
    }
  }
}

TEST(Pw85Lanes, EveryPairMatchesTheScalarSolverAndGeometry) {
  std::printf("[pw85 lanes] instruction set: %s\n", lanes_instruction_set());
  Rng rng(77);
  for (const bool stop : {true, false}) {
    for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{3}, std::size_t{4}, std::size_t{5}})
      check_list(rng, count, stop);
    check_list(rng, 3001, stop);
  }
}

}  // namespace
}  // namespace grains::contact
