// Insertion of grains where they overlap nothing (sim/insert): every grain
// placed by either method is checked here by brute force over all pairs,
// independently of the hash grid the insertion uses: sphere distances, the
// PW85 contact function for ellipsoids, the balls of clumps, the walls.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "contact/ellipsoid/pw85.hpp"
#include "sim/insert/grain_geometry.hpp"
#include "sim/insert/insert_grains.hpp"

namespace grains::sim::insert {
namespace {

using Method = InsertionConfig::Method;

// A bed of spheres of radius R: random sequential addition in [0, L]^3 (a
// plain O(n^2) loop), solid fraction about 0.3.
SceneGrains rsa_bed(double L, double R, int n, std::uint64_t seed) {
  SceneGrains s;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(R, L - R);
  for (int t = 0; t < 200000 && static_cast<int>(s.sphere_r.size()) < n; ++t) {
    const Vec3 x(u(rng), u(rng), u(rng));
    bool ok = true;
    for (const auto& y : s.sphere_x) ok = ok && (x - y).norm() >= 2 * R;
    if (!ok) continue;
    s.sphere_x.push_back(x);
    s.sphere_r.push_back(R);
  }
  return s;
}

InsertionConfig config(Method m, double r, std::int64_t count, const Vec3& lo, const Vec3& hi) {
  InsertionConfig c;
  c.method = m;
  c.grains.name = "test";
  c.grains.size.radius = r;
  c.grains.count = count;
  c.region.lo = lo;
  c.region.hi = hi;
  c.attempts = 20000;
  c.orientations = 4;
  return c;
}

Domain box(double L, std::array<bool, 3> periodic = {false, false, false}) {
  Domain d;
  d.lo = Vec3::Zero();
  d.hi = Vec3::Constant(L);
  d.periodic = periodic;
  return d;
}

contact::SymMat3 sphere_form(double r) { return {r * r, 0, 0, r * r, 0, r * r}; }

// b - a to the nearest image along periodic axes.
Vec3 delta(const Vec3& a, const Vec3& b, const Domain& d) {
  Vec3 r = b - a;
  for (int k = 0; k < 3; ++k)
    if (d.periodic[k]) r[k] -= (d.hi[k] - d.lo[k]) * std::round(r[k] / (d.hi[k] - d.lo[k]));
  return r;
}

// Everything as parts: the scene and the new grains; then all pairs checked.
struct Part {
  Vec3 x;
  double bound;
  bool ell;
  contact::SymMat3 form;
  int grain;  // -1: scene; else index of the new grain (parts of one grain do not collide)
};

bool overlap(const Part& a, const Part& b, const Domain& d) {
  const Vec3 r = delta(a.x, b.x, d);
  if (r.norm() >= a.bound + b.bound) return false;
  if (!a.ell && !b.ell) return true;
  const auto res = contact::pw85_contact(r, a.ell ? a.form : sphere_form(a.bound), b.ell ? b.form : sphere_form(b.bound));
  return res.mu2 < 1.0;
}

// Asserts that no new grain overlaps the scene, another new grain, a plane
// {x: (x - p).n >= 0} of `floors` or leaves the region.
void expect_all_free(const InsertionConfig& c, const SceneGrains& scene, const std::vector<NewGrain>& out,
                     const Domain& d, const std::vector<std::pair<Vec3, Vec3>>& planes = {}) {
  std::vector<Part> parts;
  for (std::size_t i = 0; i < scene.sphere_r.size(); ++i) parts.push_back({scene.sphere_x[i], scene.sphere_r[i], false, {}, -1});
  for (std::size_t i = 0; i < scene.ell_x.size(); ++i)
    parts.push_back({scene.ell_x[i], scene.ell_axes[i].maxCoeff(), true,
                     contact::quadratic_form(scene.ell_axes[i], scene.ell_q[i]), -1});
  const std::size_t n_scene = parts.size();
  for (std::size_t k = 0; k < out.size(); ++k) {
    const auto g = grain_parts(c.grains.shape, out[k].r, out[k].x, out[k].o);
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(out[k].x[a], c.region.lo[a] + out[k].r - 1e-12) << k;
      EXPECT_LE(out[k].x[a], c.region.hi[a] - out[k].r + 1e-12) << k;
    }
    if (g.ellipsoid) parts.push_back({g.ell_centre, g.ell_bound, true, g.form, static_cast<int>(k)});
    for (std::size_t b = 0; b < g.radii.size(); ++b) parts.push_back({g.centres[b], g.radii[b], false, {}, static_cast<int>(k)});
  }
  int bad = 0;
  for (std::size_t i = n_scene; i < parts.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (parts[j].grain == parts[i].grain) continue;
      if (overlap(parts[i], parts[j], d) && ++bad < 5) ADD_FAILURE() << "new part " << i << " overlaps part " << j;
    }
    for (const auto& [p, n] : planes) {
      const double h = parts[i].ell ? contact::support(parts[i].form, n) : parts[i].bound;
      EXPECT_GE((parts[i].x - p).dot(n), h) << "part " << i << " crosses a plane";
    }
  }
  EXPECT_EQ(bad, 0);
}

TEST(InsertGrains, SpheresInABedOverlapNothingWithBothMethods) {
  const double L = 1.0, R = 0.08;
  const auto bed = rsa_bed(L, R, 120, 3);
  ASSERT_GT(bed.sphere_r.size(), 100u);
  const Domain d = box(L);
  Walls walls;  // a floor at z = 0.05 cuts through the bed's bottom layer
  walls.of<sim::PlaneWall>().push_back({});
  walls.of<sim::PlaneWall>().back().point = Vec3(0, 0, 0.05);
  for (Method m : {Method::Fft, Method::Random}) {
    const auto c = config(m, 0.04, 60, Vec3::Zero(), Vec3::Constant(L));
    InsertStats st;
    const auto out = insert_grains(c, bed, d, walls, 11, 1, &st);
    EXPECT_GE(out.size(), 30u) << (m == Method::Fft ? "fft" : "random");
    EXPECT_EQ(st.placed, static_cast<std::int64_t>(out.size()));
    expect_all_free(c, bed, out, d, {{Vec3(0, 0, 0.05), Vec3(0, 0, 1)}});
  }
}

TEST(InsertGrains, FftFindsEveryHoleOfALattice) {
  // A simple cubic lattice of touching-but-for-1% spheres: a sphere of
  // radius 0.6 R fits only near a cube's centre (within 0.29 R along an
  // axis, 0.15 R along a diagonal), one per cube; nowhere else within the
  // lattice (the region stops at its outer centres). The field must find all
  // 27 holes; the grains are checked exactly.
  const double R = 1.0, a = 2.02 * R;
  SceneGrains s;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) {
        s.sphere_x.emplace_back(R + i * a, R + j * a, R + k * a);
        s.sphere_r.push_back(R);
      }
  const double L = 2 * R + 3 * a;
  // Nodes 1.606 + 0.101 k fall on the hole centres 2.01 + 2.02 m.
  auto c = config(Method::Fft, 0.6 * R, 40, Vec3::Constant(1.006 * R), Vec3::Constant(L - R));
  c.spacing = a / 20;
  InsertStats st;
  const auto out = insert_grains(c, s, box(L), Walls{}, 5, 1, &st);
  EXPECT_EQ(out.size(), 27u);
  EXPECT_GE(st.fields, 1);
  expect_all_free(c, s, out, box(L));
  for (const auto& g : out) {  // each at a cube's centre, within the clearance
    for (int d = 0; d < 3; ++d) {
      const double u = (g.x[d] - R) / a - 0.5;
      EXPECT_NEAR(u, std::round(u), 0.29 * R / a);
    }
  }
}

TEST(InsertGrains, EllipsoidsAmongSpheresAndEllipsoidsAgainstWalls) {
  const double L = 1.0;
  auto bed = rsa_bed(L, 0.08, 100, 9);
  // Some ellipsoids in the scene too.
  std::mt19937_64 rng(4);
  for (int k = 0; k < 6; ++k) {
    bed.ell_x.emplace_back(0.15 + 0.14 * k, 0.5, 0.93);
    bed.ell_axes.emplace_back(0.06, 0.03, 0.03);
    bed.ell_q.push_back(uniform_rotation(rng));
  }
  // Drop the spheres the ellipsoids would overlap (an invalid scene otherwise).
  SceneGrains s = bed;
  s.sphere_x.clear();
  s.sphere_r.clear();
  for (std::size_t i = 0; i < bed.sphere_r.size(); ++i)
    if (std::abs(bed.sphere_x[i].z() - 0.93) > 0.12) {
      s.sphere_x.push_back(bed.sphere_x[i]);
      s.sphere_r.push_back(bed.sphere_r[i]);
    }
  Walls walls;
  walls.of<sim::PlaneWall>().push_back({});
  walls.of<sim::PlaneWall>().back().point = Vec3(0, 0, 0.1);
  walls.of<sim::CylinderWall>().push_back({});
  walls.of<sim::CylinderWall>().back().surface = {Vec3(0.5, 0.5, 0), Vec3(0, 0, 1), 0.48, 0.0, 1.0, true};
  walls.of<sim::CylinderWall>().push_back({});  // a post in the middle: grains stay outside it
  walls.of<sim::CylinderWall>().back().surface = {Vec3(0.5, 0.5, 0), Vec3(0, 0, 1), 0.1, 0.0, 1.0, false};
  for (Method m : {Method::Fft, Method::Random}) {
    auto c = config(m, 0.06, 40, Vec3::Zero(), Vec3::Constant(L));
    c.grains.shape.kind = ShapeConfig::Kind::Ellipsoid;
    c.grains.shape.axes_rel = Vec3(1, 0.5, 0.5);  // aspect ratio 2
    InsertStats st;
    const auto out = insert_grains(c, s, box(L), walls, 21, 1, &st);
    EXPECT_GE(out.size(), 20u) << (m == Method::Fft ? "fft" : "random");
    expect_all_free(c, s, out, box(L), {{Vec3(0, 0, 0.1), Vec3(0, 0, 1)}});
    for (const auto& g : out) {  // inside the cylinder: support along the radial direction
      const auto form = contact::quadratic_form(g.r * c.grains.shape.axes_rel, g.o);
      Vec3 rad = g.x - Vec3(0.5, 0.5, g.x.z());
      const double rho = rad.norm();
      if (rho > 0) rad /= rho;
      EXPECT_LE(rho + contact::support(form, rad), 0.48 + 1e-9);
      // Clear of the post: no point of the surface (sampled) within 0.1 of the axis.
      const Eigen::Matrix3d R = g.o.toRotationMatrix();
      const Vec3 axes = g.r * c.grains.shape.axes_rel;
      double closest = 1e300;
      for (int u = 0; u < 40; ++u)
        for (int v = 0; v <= 20; ++v) {
          const double th = M_PI * v / 20, ph = 2 * M_PI * u / 40;
          const Vec3 n(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
          const Vec3 x = g.x + R * axes.cwiseProduct(n);
          closest = std::min(closest, std::hypot(x.x() - 0.5, x.y() - 0.5));
        }
      EXPECT_GE(closest, 0.1 - 1e-9);
    }
  }
}

TEST(InsertGrains, ClumpsInAPeriodicBox) {
  auto shape = std::make_shared<ClumpShape>();
  shape->centres = {Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0), Vec3(0, 0.45, 0)};  // a bent trimer, bounding radius 1
  shape->radii = {0.5, 0.5, 0.5};
  const double L = 1.0;
  const Domain d = box(L, {true, true, false});
  const auto bed = rsa_bed(L, 0.07, 150, 17);
  for (Method m : {Method::Fft, Method::Random}) {
    auto c = config(m, 0.06, 50, Vec3::Zero(), Vec3::Constant(L));
    c.grains.shape.kind = ShapeConfig::Kind::Clump;
    c.grains.shape.clump = shape;
    InsertStats st;
    const auto out = insert_grains(c, bed, d, Walls{}, 8, 1, &st);
    EXPECT_GE(out.size(), 25u) << (m == Method::Fft ? "fft" : "random");
    expect_all_free(c, bed, out, d);  // distances to the nearest periodic image
  }
}

TEST(InsertGrains, SameSeedSameGrainsAndASizeDistribution) {
  const auto bed = rsa_bed(1.0, 0.08, 100, 5);
  auto c = config(Method::Fft, 0.04, 30, Vec3::Zero(), Vec3::Constant(1.0));
  c.grains.size.kind = SizeDistribution::Kind::Uniform;
  c.grains.size.min = 0.03;
  c.grains.size.max = 0.05;
  const auto a = insert_grains(c, bed, box(1.0), Walls{}, 3, 1);
  const auto b = insert_grains(c, bed, box(1.0), Walls{}, 3, 1);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k].x, b[k].x);
  for (std::size_t k = 1; k < a.size(); ++k) EXPECT_LE(a[k].r, a[k - 1].r);  // largest first
  expect_all_free(c, bed, a, box(1.0));
}

TEST(InsertGrains, EllipsoidCoverContainsTheEllipsoid) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const Vec3& axes : {Vec3(2, 1, 1), Vec3(1, 3, 0.5), Vec3(1, 1, 1), Vec3(1, 1, 0.2)}) {
    std::vector<Vec3> c;
    std::vector<double> r;
    ellipsoid_cover(axes, c, r);
    for (int t = 0; t < 20000; ++t) {
      // A random point of the ellipsoid's surface (the hardest to cover).
      Vec3 n(u(rng), u(rng), u(rng));
      if (n.norm() < 1e-3) continue;
      n.normalize();
      const Vec3 x = axes.cwiseProduct(n);
      bool in = false;
      for (std::size_t k = 0; k < c.size() && !in; ++k) in = (x - c[k]).norm() <= r[k];
      ASSERT_TRUE(in) << axes.transpose() << " point " << x.transpose();
    }
  }
}

}  // namespace
}  // namespace grains::sim::insert
