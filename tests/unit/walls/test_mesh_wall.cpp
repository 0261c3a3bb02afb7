// Mesh walls (sim/walls/mesh_wall.hpp, contact/mesh/mesh_surface.hpp,
// contact/ellipsoid/ellipsoid_mesh.hpp): one contact per physical contact at
// faces, edges and vertices, for spheres and ellipsoids, against planes and
// brute force; a sphere rolling and sliding across a triangulated floor
// follows the plane wall's trajectory; case keys and their errors.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <random>
#include <unistd.h>
#include <hdf5.h>
#include <sstream>

#include "contact/ellipsoid/ellipsoid_mesh.hpp"
#include "contact/ellipsoid/ellipsoid_walls.hpp"
#include "contact/ellipsoid/point_ellipsoid.hpp"
#include "contact/mesh/mesh_surface.hpp"
#include "tests/support/case_errors.hpp"
#include "tests/support/mesh_files.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

using contact::MeshContact;
using contact::MeshSurface;
using sim::Vec3;
namespace fs = std::filesystem;

MeshSurface surface(const Tri& m, bool one_sided = false) { return MeshSurface(m.v, m.f, one_sided); }

std::vector<MeshContact> sphere(const MeshSurface& s, const Vec3& x, double r) {
  std::vector<std::uint32_t> tris;
  s.near(x, r, tris);
  std::vector<MeshContact> out(16);
  const int n = s.sphere_contacts(x, r, tris, out.data(), 16);
  out.resize(static_cast<std::size_t>(std::min(n, 16)));
  return out;
}

// ---- spheres ----

TEST(MeshSurfaceSphere, FlatTriangulatedFloorGivesThePlaneContactEverywhere) {
  // 8 x 8 cells of alternating diagonals on [0, 1]^2: random centres, and
  // centres exactly over edges, diagonals and vertices.
  const auto s = surface(grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 8, 8));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.05, 0.95), h(0.01, 0.049);
  std::vector<Vec3> xs;
  for (int k = 0; k < 5000; ++k) xs.emplace_back(u(rng), u(rng), h(rng));
  for (int i = 1; i < 8; ++i)
    for (int j = 1; j < 8; ++j) {
      xs.emplace_back(i / 8.0, j / 8.0, 0.03);            // a vertex
      xs.emplace_back(i / 8.0, (j + 0.37) / 8.0, 0.03);   // an edge
      xs.emplace_back((i + 0.5) / 8.0, (j + 0.5) / 8.0, 0.03);  // a diagonal's midpoint
    }
  for (const auto& x : xs) {
    const auto c = sphere(s, x, 0.05);
    ASSERT_EQ(c.size(), 1u) << x.transpose();
    EXPECT_NEAR(c[0].depth, 0.05 - x.z(), 1e-15);
    EXPECT_NEAR((c[0].normal - Vec3(0, 0, 1)).norm(), 0, 1e-15);
    EXPECT_NEAR((c[0].point - Vec3(x.x(), x.y(), 0)).norm(), 0, 1e-15);
  }
  // Below the floor (two-sided): pushed down.
  const auto c = sphere(s, Vec3(0.5, 0.5, -0.02), 0.05);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR((c[0].normal - Vec3(0, 0, -1)).norm(), 0, 1e-15);
}

// A sheet folded along x = 0: z = slope |x| (a valley) or -slope |x| (a ridge).
Tri folded(double slope, int n = 4) {
  Tri m = grid(Vec3(-1, -1, slope), Vec3(1, 0, -slope), Vec3(0, 2, 0), n, n);
  m.add(grid(Vec3(0, -1, 0), Vec3(1, 0, slope), Vec3(0, 2, 0), n, n));
  m.weld();
  return m;
}

TEST(MeshSurfaceSphere, ConvexRidgeGivesOneEdgeContact) {
  const auto s = surface(folded(-0.5));
  // Over the ridge (any y, also over the ridge's vertices): one contact, at the ridge, straight up.
  for (double y : {-0.5, -0.25, 0.0, 0.1, 0.3}) {
    const auto c = sphere(s, Vec3(0, y, 0.1), 0.15);
    ASSERT_EQ(c.size(), 1u) << y;
    EXPECT_EQ(c[0].feature, y == -0.5 || y == 0.0 ? 2 : 1);  // the grid's vertices lie at y = -1 + k/2
    EXPECT_NEAR((c[0].point - Vec3(0, y, 0)).norm(), 0, 1e-15);
    EXPECT_NEAR(c[0].depth, 0.05, 1e-15);
  }
  // Slightly to one side but still nearest to the ridge: the edge, normal tilted.
  const auto c = sphere(s, Vec3(0.02, 0.1, 0.1), 0.15);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].feature, 1);
  EXPECT_NEAR((c[0].normal - Vec3(0.02, 0, 0.1).normalized()).norm(), 0, 1e-14);
  // Over one flank (inside its face region): that face only.
  const Vec3 x(0.3, 0.1, -0.15 + 0.1 * std::sqrt(1.25));  // 0.1 from the flank z = -0.5 x, above x = 0.3 - ...
  const auto f = sphere(s, x, 0.12);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].feature, 0);
}

TEST(MeshSurfaceSphere, ConcaveValleyGivesOneContactPerFlank) {
  const auto s = surface(folded(0.5));
  const auto c = sphere(s, Vec3(0, 0.1, 0.2), 0.2);
  ASSERT_EQ(c.size(), 2u);
  for (const auto& k : c) {
    EXPECT_EQ(k.feature, 0);
    EXPECT_NEAR(k.depth, 0.2 - 0.2 / std::sqrt(1.25), 1e-14);  // distance 0.2 cos(atan 0.5)
  }
  EXPECT_NEAR(c[0].normal.x(), -c[1].normal.x(), 1e-14);
}

TEST(MeshSurfaceSphere, BoxCornersOutsideAndInside) {
  Tri box = open_box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  box.weld();
  const auto s = surface(box);
  // Outside the convex corner (1, 1, 0) of the box, diagonally: one vertex contact.
  const Vec3 x = Vec3(1, 1, 0) + Vec3(1, 1, -1).normalized() * 0.1;
  auto c = sphere(s, x, 0.15);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].feature, 2);
  EXPECT_NEAR(c[0].depth, 0.05, 1e-14);
  // Outside an edge of the box (x = 1, z = 0), at mid y: one edge contact.
  c = sphere(s, Vec3(1.05, 0.5, -0.05), 0.1);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].feature, 1);
  // Inside the corner (0, 0, 0): the floor and two walls, three face contacts, deepest first.
  c = sphere(s, Vec3(0.05, 0.06, 0.07), 0.08);
  ASSERT_EQ(c.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(c[static_cast<std::size_t>(k)].feature, 0);
    EXPECT_NEAR(c[static_cast<std::size_t>(k)].depth, 0.03 - 0.01 * k, 1e-14);
  }
}

TEST(MeshSurfaceSphere, ContactsAreLocalMinimaOfTheDistanceAgainstSampledSurfaces) {
  // Random spheres against a bumpy random surface: every contact point is a
  // local minimum of the distance from the centre over the triangles that
  // hold it (no nearer sampled point of theirs near it), and no two contacts
  // are at the same point.
  Tri m = grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 6, 6);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> bump(-0.08, 0.08);
  for (auto& v : m.v) v.z() += bump(rng);
  const auto s = surface(m);
  std::uniform_real_distribution<double> u(0.15, 0.85), h(-0.05, 0.2);
  const int N = 60;
  std::vector<std::vector<Vec3>> samples(m.f.size());
  for (std::size_t t = 0; t < m.f.size(); ++t) {
    const auto& f = m.f[t];
    for (int i = 0; i <= N; ++i)
      for (int j = 0; i + j <= N; ++j)
        samples[t].push_back(m.v[f[0]] + (m.v[f[1]] - m.v[f[0]]) * (double(i) / N) + (m.v[f[2]] - m.v[f[0]]) * (double(j) / N));
  }
  int checked = 0, features[3] = {0, 0, 0};
  for (int k = 0; k < 400; ++k) {
    const Vec3 x(u(rng), u(rng), h(rng));
    const double r = 0.12;
    const auto c = sphere(s, x, r);
    for (std::size_t a = 0; a < c.size(); ++a) {
      const double d = (x - c[a].point).norm();
      EXPECT_NEAR(d, r - c[a].depth, 1e-14);
      for (std::size_t b = a + 1; b < c.size(); ++b) EXPECT_GT((c[a].point - c[b].point).norm(), 1e-9);
      for (std::size_t t = 0; t < m.f.size(); ++t) {
        const auto& f = m.f[t];
        const auto tp = contact::closest_point_on_triangle(c[a].point, m.v[f[0]], m.v[f[1]], m.v[f[2]]);
        if ((tp.point - c[a].point).norm() > 1e-12) continue;  // does not hold the point
        for (const auto& p : samples[t])
          if ((p - c[a].point).norm() < 0.03) {
          EXPECT_GE((x - p).norm(), d - 1e-12) << "feature " << c[a].feature;
        }
      }
      ++checked;
      ++features[c[a].feature];
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(features[1], 5);  // edges were among them
}

// ---- ellipsoids ----

contact::Ellipsoid tilted(const Vec3& c, const Vec3& a, double angle, const Vec3& axis) {
  return {c, a, contact::Quat(Eigen::AngleAxisd(angle, axis.normalized()))};
}

std::vector<MeshContact> ellipsoid(const MeshSurface& s, const contact::Ellipsoid& e) {
  std::vector<std::uint32_t> tris;
  s.near(e.centre, e.semi_axes.maxCoeff(), tris);
  std::vector<MeshContact> out(16);
  const int n = contact::ellipsoid_mesh_contacts(s, e, tris, out.data(), 16);
  out.resize(static_cast<std::size_t>(std::min(n, 16)));
  return out;
}

TEST(MeshSurfaceEllipsoid, TriangulatedFloorGivesThePlaneContact) {
  const auto s = surface(grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 8, 8));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.2, 0.8), ang(0, M_PI), h(0.02, 0.05);
  std::normal_distribution<double> g;
  for (int k = 0; k < 2000; ++k) {
    const auto e = tilted(Vec3(u(rng), u(rng), h(rng)), Vec3(0.06, 0.03, 0.02), ang(rng), Vec3(g(rng), g(rng), g(rng)));
    bool touching = false;
    const auto p = contact::ellipsoid_plane_contact(e, contact::Plane{Vec3(0, 0, 0), Vec3(0, 0, 1)}, &touching);
    const auto c = ellipsoid(s, e);
    if (!touching) {
      EXPECT_TRUE(c.empty());
      continue;
    }
    ASSERT_EQ(c.size(), 1u) << k;
    EXPECT_NEAR(c[0].depth, p.overlap, 1e-15);
    EXPECT_NEAR((c[0].normal - p.normal).norm(), 0, 1e-15);
    EXPECT_NEAR((c[0].point - p.point).norm(), 0, 1e-15);
    EXPECT_NEAR(c[0].radius, p.radius, 1e-12 * p.radius);
  }
}

// The deepest point of the surface inside the body by brute force: the
// largest depth -(signed distance) over dense samples of the triangles.
double sampled_depth(const Tri& m, const contact::Ellipsoid& e, Vec3* at) {
  double best = 0;
  const int N = 200;
  for (const auto& t : m.f)
    for (int i = 0; i <= N; ++i)
      for (int j = 0; i + j <= N; ++j) {
        const Vec3 p = m.v[t[0]] + (m.v[t[1]] - m.v[t[0]]) * (double(i) / N) + (m.v[t[2]] - m.v[t[0]]) * (double(j) / N);
        const double d = -contact::closest_point_on_ellipsoid(p, e).signed_distance;
        if (d > best) best = d, *at = p;
      }
  return best;
}

TEST(MeshSurfaceEllipsoid, AcrossARidgeOneEdgeContactAtTheSampledDeepestPoint) {
  const Tri m = folded(-0.5, 2);
  const auto s = surface(m);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> ang(0, M_PI), y(-0.3, 0.3);
  std::normal_distribution<double> g;
  int edges = 0;
  std::uniform_real_distribution<double> depth(0.0005, 0.004);
  for (int k = 0; k < 40; ++k) {
    auto e = tilted(Vec3(0, y(rng), 0), Vec3(0.12, 0.06, 0.04), ang(rng), Vec3(g(rng), g(rng), g(rng)));
    // Raise it until the ridge point below its centre is `depth` inside (DEM overlaps are small).
    e.centre.z() = 0.5;
    const Vec3 top(0, e.centre.y(), 0);
    const double want = depth(rng);
    for (int it = 0; it < 200; ++it) {
      const double sd = contact::closest_point_on_ellipsoid(top, e).signed_distance;
      if (std::abs(sd + want) < 1e-12) break;
      e.centre.z() -= 0.5 * (sd + want);
    }
    const auto c = ellipsoid(s, e);
    ASSERT_LE(c.size(), 1u);
    for (const auto& k2 : c) {
      EXPECT_TRUE(std::isfinite(k2.depth) && k2.normal.allFinite() && k2.point.allFinite());
      if (k2.feature != 1) continue;
      ++edges;
      // The deepest point of the whole surface: no sample deeper, none much
      // shallower than a sample spacing (the depth is 1-Lipschitz) ...
      Vec3 at;
      const double d = sampled_depth(m, e, &at);
      EXPECT_GE(k2.depth, d - 1e-12);
      EXPECT_LE(k2.depth, d + 0.005);
      // ... and of the ridge, sampled every 1e-6 m about it.
      double ridge = 0;
      for (int j = -20000; j <= 20000; ++j)
        ridge = std::max(ridge, -contact::closest_point_on_ellipsoid(Vec3(0, k2.point.y() + 1e-6 * j, 0), e).signed_distance);
      EXPECT_NEAR(k2.depth, ridge, 1e-9);
      EXPECT_NEAR(k2.point.x(), 0, 1e-15);
      EXPECT_NEAR(k2.point.z(), 0, 1e-15);
    }
  }
  EXPECT_GT(edges, 10);
}

TEST(MeshSurfaceEllipsoid, LyingOnAVertexOfAPyramid) {
  // A pyramid's apex (0, 0, 0) pointing up; the ellipsoid above it touches the apex only.
  Tri m;
  m.v = {Vec3(0, 0, 0), Vec3(1, 0, -1), Vec3(0, 1, -1), Vec3(-1, 0, -1), Vec3(0, -1, -1)};
  m.f = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
  const auto s = surface(m);
  const auto e = tilted(Vec3(0.01, -0.02, 0.03), Vec3(0.08, 0.05, 0.04), 0.7, Vec3(1, 2, 3));
  const auto c = ellipsoid(s, e);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].feature, 2);
  EXPECT_NEAR(c[0].depth, -contact::closest_point_on_ellipsoid(Vec3(0, 0, 0), e).signed_distance, 1e-14);
}

}  // namespace
}  // namespace grains::test

namespace grains::test {
namespace {

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("grains_mesh_wall_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d / name;
}

// One sphere thrown spinning and sliding along a floor (friction 0.4):
// it slides, then rolls, across the cells of a triangulated floor or on a plane.
std::vector<Vec3> throw_sphere(const std::string& floor, const Vec3& v0, double end) {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.02, -0.02, -0.01], max: [0.1, 0.1, 0.03]}\ngravity: [0, 0, -9.81]\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0.4)
    << "particles:\n" << single("ball", "m", Vec3(0.001, 0.002, 0.000995), 0.001, v0)
    << "walls:\n" << floor << "time: {dt: 2e-6, end: " << end << "}\n";
  auto s = from_yaml(y.str());
  s.pipeline.initialize(s.scene);
  std::vector<Vec3> path;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    if (s.scene.clock.step % 500 == 0) path.push_back(s.scene.particles.x[0]);
  }
  return path;
}

TEST(MeshWall, SphereSlidingAndRollingAcrossATriangulatedFloorFollowsThePlane) {
  const fs::path off = scratch("floor.off");
  write_off(off, grid(Vec3(-0.01, -0.01, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), 40, 40));  // 2.5 mm cells
  const Vec3 v0(0.3, 0.17, 0);
  const auto plane = throw_sphere("  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}\n", v0, 0.2);
  const auto mesh = throw_sphere("  - {type: mesh, file: " + off.string() + ", material: m}\n", v0, 0.2);
  ASSERT_EQ(plane.size(), mesh.size());
  const double travelled = (plane.back() - plane.front()).norm();
  EXPECT_GT(travelled, 0.03);  // over a dozen cells, their edges and vertices
  double worst = 0;
  for (std::size_t k = 0; k < plane.size(); ++k) worst = std::max(worst, (plane[k] - mesh[k]).norm());
  std::cout << "sphere: travelled " << travelled << " m, largest distance from the plane run's path " << worst << " m\n";
  for (std::size_t k = 0; k < plane.size(); ++k)
    EXPECT_LT((plane[k] - mesh[k]).norm(), 1e-6 * travelled) << k;
}

}  // namespace
}  // namespace grains::test

namespace grains::test {
namespace {

std::string drum_case(const fs::path& off, const std::string& motion, double end, const std::string& extra = "") {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.012, -0.005, -0.012], max: [0.012, 0.005, 0.012]}\ngravity: [0, 0, -9.81]\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0.5, 0.05)
    << "particles:\n  - {name: beads, material: m, radius: 0.0005, count: 150, placement: {type: random_fill, "
       "region: {min: [-0.006, -0.0024, -0.0068], max: [0.006, 0.0024, 0.001]}, seed: 5}}\n"
    << "walls:\n  - {type: mesh, name: drum, file: " << off.string() << ", material: m" << motion << "}\n"
    << "time: {dt: 1e-5, end: " << end << "}\n" << extra;
  return y.str();
}

TEST(MeshWall, RotatingDrumDragsItsBedUpFromItsStartOverItsRamp) {
  const fs::path off = scratch("drum.off");
  write_off(off, drum(Vec3(0, 0, 0), 0.01, 0.006, 48, 3));
  // Settle at rest for 0.05 s, then spin up over 0.02 s to 20 rad/s about +y
  // (x towards -z at the bottom... the bed's centre moves to -x... see below).
  auto s = from_yaml(drum_case(off, ", axis: [0, 1, 0], angular_velocity: 20, start: 0.05, ramp: 0.02", 0.12));
  s.pipeline.initialize(s.scene);
  const auto& w = s.scene.walls.of<sim::MeshWall>()[0];
  auto centre = [&] {
    Vec3 c = Vec3::Zero();
    for (std::size_t i = 0; i < s.scene.particles.n_owned(); ++i) c += s.scene.particles.x[i];
    return Vec3(c / static_cast<double>(s.scene.particles.n_owned()));
  };
  while (s.scene.clock.time < 0.0499) s.pipeline.step(s.scene);
  EXPECT_TRUE(w.R.isIdentity(0));  // at rest before its start
  const Vec3 rest = centre();
  EXPECT_NEAR(rest.x(), 0, 4e-4);  // a symmetric bed
  while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
  // Turned by 20 (0.12 - 0.05 - 0.01) rad = 1.2 rad; the drum's surface at
  // the bottom moves along +y x (0, 0, -r) = -x... the bed is dragged up the
  // side the bottom moves towards: its centre of mass moves to -x and up.
  EXPECT_NEAR(Eigen::AngleAxisd(w.R).angle(), 20 * (0.12 - 0.05 - 0.01), 1e-9);
  const Vec3 now = centre();
  EXPECT_EQ(s.scene.particles.n_owned(), 150u);  // none escaped through the mesh
  EXPECT_LT(now.x(), rest.x() - 1e-3);
  EXPECT_GT(now.z(), rest.z());
  for (std::size_t i = 0; i < s.scene.particles.n_owned(); ++i)
    EXPECT_LT(std::hypot(s.scene.particles.x[i].x(), s.scene.particles.x[i].z()), 0.01);
}

TEST(MeshWall, WallLoadIsTheBedsWeightAndItsTorqueAboutTheAxis) {
  const fs::path off = scratch("drum_load.off");
  write_off(off, drum(Vec3(0, 0, 0), 0.01, 0.006, 48, 3));
  auto s = from_yaml(drum_case(off, "", 0.2));
  s.pipeline.initialize(s.scene);
  s.scene.wall_loads.assign(1, {});
  sim::WallLoad l;  // averaged over the last 0.05 s
  int n = 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    if (s.scene.clock.time < 0.15) continue;
    l.force += s.scene.wall_loads[0].force;
    l.torque += s.scene.wall_loads[0].torque;
    ++n;
  }
  l.force /= n;
  l.torque /= n;
  double m = 0;
  Vec3 mx = Vec3::Zero();
  for (std::size_t i = 0; i < s.scene.particles.n_owned(); ++i) {
    m += s.scene.particles.mass[i];
    mx += s.scene.particles.mass[i] * s.scene.particles.x[i];
  }
  // At rest the drum carries the bed's weight, and the torque of that weight about its centre.
  EXPECT_NEAR(l.force.z(), -9.81 * m, 0.01 * 9.81 * m);
  EXPECT_NEAR(l.force.x(), 0, 0.01 * 9.81 * m);
  const Vec3 weight_torque = mx.cross(Vec3(0, 0, -9.81));
  EXPECT_NEAR(l.torque.y(), weight_torque.y(), 0.02 * 9.81 * m * 0.01);
}

}  // namespace
}  // namespace grains::test

namespace grains::test {
namespace {

std::string floor_case(const std::string& wall, const std::string& particles = "") {
  std::ostringstream y;
  y << "domain: {min: [-0.02, -0.02, -0.01], max: [0.1, 0.1, 0.03]}\ngravity: [0, 0, -9.81]\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0.4)
    << "particles:\n" << (particles.empty() ? single("ball", "m", Vec3(0.01, 0.01, 0.002), 0.001, Vec3::Zero()) : particles)
    << "walls:\n  - {type: mesh, material: m, " << wall << "}\ntime: {dt: 2e-6, end: 0.001}\n";
  return y.str();
}

TEST(MeshWallCase, BadInputGetsLocatedErrors) {
  const fs::path off = scratch("ok.off");
  write_off(off, grid(Vec3(-0.01, -0.01, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), 4, 4));
  // Missing file: named, located at the key.
  auto e = errors_of(floor_case("file: /nonexistent/hopper.stl"));
  EXPECT_NE(e.find("case.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("hopper.stl"), std::string::npos) << e;
  // A broken file: the reader's message, with its line.
  const fs::path bad = scratch("bad.off");
  {
    std::ofstream o(bad);
    o << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 x\n3 0 1 2\n";
  }
  e = errors_of(floor_case("file: " + bad.string()));
  EXPECT_NE(e.find("bad.off"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot use the mesh"), std::string::npos) << e;
  // Millimetres read as metres: 1000 times the domain.
  e = errors_of(floor_case("file: " + off.string() + ", scale: 1000"));
  EXPECT_NE(e.find("times the domain's size"), std::string::npos) << e;
  EXPECT_NE(e.find("scale: 0.001"), std::string::npos) << e;
  // Outside the domain.
  e = errors_of(floor_case("file: " + off.string() + ", translate: [0, 0, 5]"));
  EXPECT_NE(e.find("lies outside the domain"), std::string::npos) << e;
  // A rotation axis of zero length.
  e = errors_of(floor_case("file: " + off.string() + ", axis: [0, 0, 0], angular_velocity: 1"));
  EXPECT_NE(e.find("must not be the zero vector"), std::string::npos) << e;
  e = errors_of(floor_case("file: " + off.string() + ", angular_velocity: 1, rpm: 10"));
  EXPECT_NE(e.find("not both"), std::string::npos) << e;
  e = errors_of(floor_case("file: " + off.string() + ", vibration_amplitude: [0, 0, 0.001]"));
  EXPECT_NE(e.find("vibration_frequency > 0"), std::string::npos) << e;
  e = errors_of(floor_case("file: " + off.string()) + "output: {wall_loads: {every: 0.01, every_steps: 10}}\n");
  EXPECT_NE(e.find("output.wall_loads"), std::string::npos) << e;
  EXPECT_NE(e.find("not both"), std::string::npos) << e;
  e = errors_of(floor_case("file: " + off.string() + ", contacts_per_particle: 40"));
  EXPECT_NE(e.find("contacts_per_particle"), std::string::npos) << e;
  // A particle starting inside the mesh beyond the tolerance.
  e = errors_of(floor_case("file: " + off.string(), single("ball", "m", Vec3(0.01, 0.01, 0.0005), 0.001, Vec3::Zero())));
  EXPECT_NE(e.find("inside the mesh"), std::string::npos) << e;
  EXPECT_NE(e.find("overlap_tolerance"), std::string::npos) << e;
  // A mesh with zero-area faces: dropped, with a warning; the rest works.
  const fs::path degenerate = scratch("degenerate.off");
  Tri d = grid(Vec3(-0.01, -0.01, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), 2, 2);
  d.f.push_back({0, 0, 1});
  write_off(degenerate, d);
  auto ok = from_yaml(floor_case("file: " + degenerate.string()));
  EXPECT_EQ(ok.scene.walls.of<sim::MeshWall>()[0].surface->triangles(), 8u);
  bool warned = false;
  for (const auto& w : ok.c.scene.warnings) warned = warned || w.find("dropped") != std::string::npos;
  EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace grains::test

#include "io/checkpoint/checkpoint.hpp"
#include "tests/unit/checkpoint/checkpoint_scene.hpp"

namespace grains::test {
namespace {

TEST(MeshWall, RotatingDrumContinuesBitwiseFromItsCheckpoints) {
  TempDir tmp("mesh_drum");
  const fs::path off = tmp.path / "drum.off";
  write_off(off, drum(Vec3(0, 0, 0), 0.01, 0.006, 48, 3));
  // Checkpoints during the ramp (step 2000, t = 0.02 s) and at full speed (4000).
  const std::string text =
      drum_case(off, ", axis: [0, 1, 0], angular_velocity: 20, start: 0.01, ramp: 0.02", 0.06,
                "output: {every: 0.02, progress: false, wall_loads: {every_steps: 500}}\n"
                "checkpoint: {every_steps: 2000, keep: 10}\n");
  auto full = make(text);
  io::RunOptions o;
  o.quiet = true;
  o.out_dir = tmp.path / "full";
  io::run(full, o);
  for (const std::int64_t at : {2000, 4000}) {
    auto part = make(text);
    io::RunOptions p = o;
    p.out_dir = tmp.path / ("part" + std::to_string(at));
    p.restart = tmp.path / "full" / "checkpoints" / io::checkpoint_name(at);
    io::run(part, p);
    expect_same_state(full.scene, part.scene);
    const auto& a = full.scene.walls.of<sim::MeshWall>()[0];
    const auto& b = part.scene.walls.of<sim::MeshWall>()[0];
    EXPECT_EQ(std::memcmp(&a.motion_time, &b.motion_time, sizeof(double)), 0);
    EXPECT_TRUE(a.R == b.R && a.T == b.T);
    EXPECT_EQ(full.scene.neighbors.wall_items, part.scene.neighbors.wall_items);
  }
  // Resumed in its own folder, the run writes the same wall loads: the rows
  // before the checkpoint are kept, those after written again.
  const std::string loads = read_text(tmp.path / "full" / "wall_loads.csv");
  EXPECT_GT(std::count(loads.begin(), loads.end(), '\n'), 12);
  {
    auto again = make(text);
    io::RunOptions p = o;
    p.restart = tmp.path / "full" / "checkpoints" / io::checkpoint_name(2000);
    io::run(again, p);
  }
  EXPECT_EQ(read_text(tmp.path / "full" / "wall_loads.csv"), loads);
  // A mesh with another triangle count than the checkpoint's is refused.
  write_off(off, drum(Vec3(0, 0, 0), 0.01, 0.006, 40, 3));
  auto other = make(text);
  EXPECT_THROW(io::read_checkpoint(tmp.path / "full" / "checkpoints" / io::checkpoint_name(2000), other.scene),
               io::CheckpointError);
}

}  // namespace
}  // namespace grains::test

namespace grains::test {
namespace {

// One grain of `shape` thrown onto a floor (a plane, or a 40 x 40 triangulated
// mesh of the same plane): it lands, bounces, slides and rolls across many
// cells. The trajectory of its centre, every 0.5 ms.
std::vector<Vec3> throw_grain(const std::string& shape, const std::string& floor) {
  std::ostringstream y;
  y.precision(17);
  y << "domain: {min: [-0.02, -0.02, -0.01], max: [0.1, 0.1, 0.03]}\ngravity: [0, 0, -9.81]\n"
    << "materials:\n" << material("m", 2500, 1e7, 0.3, 0.5, 0.4)
    << "particles:\n  - {name: g, material: m, radius: 0.001, count: 1, velocity: [0.3, 0.17, -0.1], shape: " << shape
    << ", placement: {type: lattice, region: {min: [0.0, 0.0, 0.002], max: [0.0035, 0.0035, 0.0055]}}}\n"
    << "walls:\n" << floor << "time: {dt: 2e-6, end: 0.15}\n";
  auto s = from_yaml(y.str());
  s.pipeline.initialize(s.scene);
  std::vector<Vec3> path;
  const bool clump = s.scene.bodies.size() > 0;
  while (s.scene.clock.step < s.scene.clock.n_steps) {
    s.pipeline.step(s.scene);
    if (s.scene.clock.step % 250 == 0) path.push_back(clump ? s.scene.bodies.x[0] : s.scene.particles.x[0]);
  }
  return path;
}

void expect_same_path(const std::string& shape) {
  const fs::path off = scratch("floor_grain.off");
  write_off(off, grid(Vec3(-0.01, -0.01, 0), Vec3(0.1, 0, 0), Vec3(0, 0.1, 0), 40, 40));
  const auto plane = throw_grain(shape, "  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}\n");
  const auto mesh = throw_grain(shape, "  - {type: mesh, file: " + off.string() + ", material: m}\n");
  ASSERT_EQ(plane.size(), mesh.size());
  const double travelled = (plane.back() - plane.front()).norm();
  EXPECT_GT(travelled, 0.02) << shape;
  double worst = 0;
  for (std::size_t k = 0; k < plane.size(); ++k) {
    ASSERT_TRUE(mesh[k].allFinite());
    worst = std::max(worst, (plane[k] - mesh[k]).norm());
  }
  std::cout << shape << ": travelled " << travelled << " m, largest distance from the plane run's path " << worst
            << " m\n";
  EXPECT_LT(worst, 1e-6 * travelled) << shape;
}

TEST(MeshWall, EllipsoidSlidingAcrossATriangulatedFloorFollowsThePlane) {
  expect_same_path("{type: ellipsoid, aspect_ratio: 2, orientation: random}");
}

TEST(MeshWall, ClumpSlidingAcrossATriangulatedFloorFollowsThePlane) {
  expect_same_path("{type: clump, mesh: " + std::string(GRAINS_SOURCE_DIR) +
                   "/cases/pour_clumps/cube.off, grid: 4, orientation: random}");
}

TEST(MeshWall, SurfaceMemoryPerTriangle) {
  // What every rank holds of a mesh wall (the whole mesh: vertices, faces,
  // normals, topology, hierarchy), per triangle, for a large open mesh.
  const auto m = grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 224, 224);  // 100,352 triangles
  const MeshSurface s(m.v, m.f, false);
  const double per = static_cast<double>(s.bytes()) / static_cast<double>(s.triangles());
  std::cout << s.triangles() << " triangles: " << s.bytes() / 1e6 << " MB, " << per << " bytes per triangle\n";
  EXPECT_LT(per, 400.0);  // measured 2026-11-26: 355 (leaves of 2 triangles); 256 (one record of planes per triangle, leaves of 8); 2026-11-28: 320 (a corner in that record)
}

TEST(MeshWall, NearItemsThatDoNotFitItsNearListAreAnError) {
  // The wall stage reads a mesh wall's near triangles by row without a
  // check per row: a near list and items that disagree (a bug, or state
  // restored wrongly) stop the step with the wall's name, before any row.
  Tri m = grid(Vec3(-0.01, -0.01, 0), Vec3(0.02, 0, 0), Vec3(0, 0.02, 0), 4, 4);
  const fs::path off = scratch("floor_items.off");
  write_off(off, m);
  auto s = from_yaml("domain: {min: [-0.011, -0.011, -0.001], max: [0.011, 0.011, 0.021]}\nmaterials:\n" +
                     material("m", 2500, 1e7, 0.3, 0.9, 0.5) + "particles:\n" +
                     single("b", "m", Vec3(0, 0, 0.00101), 0.001, Vec3(0, 0, 0)) +
                     "walls:\n  - {type: mesh, name: floor, file: " + off.string() +
                     ", material: m}\ntime: {dt_rayleigh: 0.1, end: 0.05}\n");
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  s.pipeline.step(sc);
  ASSERT_EQ(sc.neighbors.wall_near.at(0).size(), 1u);
  ASSERT_EQ(sc.neighbors.wall_items.at(0).start.size(), 2u);
  // A checkpoint whose items were lost is refused at restore, saying which.
  const fs::path h5 = scratch("floor_items.h5");
  io::write_checkpoint(h5, sc, {"floor.yaml", "text", "effective", {}, {}, {}, {}});
  {
    const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    EXPECT_GE(H5Ldelete(f, "/neighbor/wall_items/0", H5P_DEFAULT), 0);
    H5Fclose(f);
  }
  try {
    (void)io::read_checkpoint(h5, sc);
    FAIL() << "no error";
  } catch (const io::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("wall 0 (floor) has a near list but no near items, /neighbor/wall_items/0 "
                                         "(corrupt checkpoint)"),
              std::string::npos)
        << e.what();
  }
  sc.neighbors.wall_items[0].start.pop_back();
  try {
    s.pipeline.step(sc);
    FAIL() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("wall floor: its near items do not match its near list"), std::string::npos)
        << e.what();
  }
}

TEST(MeshWall, OneSlotIsFreedWhenItsContactEnds) {
  // contacts_per_particle: 1. A sphere bounces off a triangulated floor, flies
  // and strikes a triangulated side wall: in flight its slot is free (no mask,
  // no normal, no spring), and the wall's contact takes it (its normal the
  // wall's) instead of finding it held by the floor's and going without history.
  Tri m = grid(Vec3(-0.01, -0.01, 0), Vec3(0.03, 0, 0), Vec3(0, 0.02, 0), 4, 4);
  m.add(grid(Vec3(0.01, -0.01, 0), Vec3(0, 0.02, 0), Vec3(0, 0, 0.02), 2, 2));
  const fs::path off = scratch("floor_and_side.off");
  write_off(off, m);
  auto s = from_yaml("domain: {min: [-0.011, -0.011, -0.001], max: [0.021, 0.011, 0.021]}\nmaterials:\n" +
                     material("m", 2500, 1e7, 0.3, 0.9, 0.5) + "particles:\n" +
                     single("b", "m", Vec3(0, 0, 0.0013), 0.001, Vec3(0.3, 0, -0.1)) +
                     "walls:\n  - {type: mesh, file: " + off.string() +
                     ", material: m, contacts_per_particle: 1}\ntime: {dt_rayleigh: 0.1, end: 0.05}\n");
  auto& sc = s.scene;
  s.pipeline.initialize(sc);
  const auto& p = sc.particles;
  ASSERT_EQ(p.wall_tag_size(), 4);  // the mask and one slot's normal
  bool floor = false, flight = false, side = false;
  while (sc.clock.step < sc.clock.n_steps && !side) {
    s.pipeline.step(sc);
    const double* tag = p.wall_tags.data();
    const double* hist = p.wall_history.data();
    const double x = p.x[0].x(), z = p.x[0].z();
    if (z < 0.001) {  // on the floor
      floor = true;
      EXPECT_EQ(tag[0], 1.0);
      EXPECT_NEAR(tag[3], 1.0, 1e-12);
    } else if (floor && x < 0.009 && z > 0.0011) {  // in flight
      flight = true;
      EXPECT_EQ(tag[0], 0.0) << "t = " << sc.clock.time;
      EXPECT_EQ(Vec3(tag[1], tag[2], tag[3]), Vec3::Zero());
      EXPECT_EQ(Vec3(hist[0], hist[1], hist[2]), Vec3::Zero());
    } else if (x > 0.009) {  // against the side
      side = true;
      EXPECT_EQ(tag[0], 1.0);
      EXPECT_NEAR(tag[1], -1.0, 1e-12);
      EXPECT_NE(Vec3(hist[0], hist[1], hist[2]), Vec3::Zero()) << "the side's contact has its spring";
    }
  }
  EXPECT_TRUE(floor && flight && side);
}

TEST(MeshSurfaceSphere, FaceContactTouchesWithinTheRadiusOnEitherSide) {
  // face_contact's answer (face_touches): |s| < r, s the centre's distance
  // along the contact's normal. Two-sided, the normal turns towards the
  // centre; one-sided it does not, and a centre behind the face by less than
  // r is pushed out through it (depth r - s > r); by r or more, none. A
  // graze at r is none. sphere_contacts gives what it says.
  Tri m = grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 2, 2);
  const double r = 0.1;
  for (const bool one : {false, true}) {
    const auto s = surface(m, one);
    for (const double z : {0.999 * r, 0.5 * r, r, -0.5 * r, -0.999 * r, -r, -1.5 * r}) {
      const Vec3 x(0.3, 0.1, z);  // over a face, off its edges
      MeshContact c;
      const bool touches = s.face_contact(x, r, 0, c);
      EXPECT_EQ(touches, std::abs(z) < r) << "one-sided " << one << ", z " << z;
      const Vec3 n = one || z >= 0 ? Vec3(0, 0, 1) : Vec3(0, 0, -1);
      EXPECT_EQ(c.normal, n);
      EXPECT_DOUBLE_EQ(c.depth, one ? r - z : r - std::abs(z));
      EXPECT_EQ(c.point, Vec3(0.3, 0.1, 0));
      const auto found = sphere(s, x, r);
      ASSERT_EQ(found.size(), touches ? 1u : 0u) << "one-sided " << one << ", z " << z;
      if (touches) {
        EXPECT_EQ(found[0].normal, n);
      }
    }
  }
}

TEST(MeshSurfaceSearch, NearFindsExactlyTheTrianglesWithinReach) {
  // The hierarchy splits at the middle of the centroids' extent (the median
  // below depth 32): a mesh of far-apart parts, and one whose triangles
  // crowd geometrically towards a point (each split leaves one side nearly
  // empty: the depth cap), against the exact distance of every triangle.
  Tri parts = grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 3, 3);
  parts.add(grid(Vec3(40, 0, 0), Vec3(2, 0, 0), Vec3(0, 0, 2), 60, 60));
  Tri crowd;
  for (int k = 0; k < 200; ++k) {
    const double a = std::pow(0.8, k), b = 0.9 * a;
    const int n = static_cast<int>(crowd.v.size());
    crowd.v.insert(crowd.v.end(), {Vec3(b, 0, 0), Vec3(a, 0, 0), Vec3(a, b, 0.1 * a)});
    crowd.f.push_back({n, n + 1, n + 2});
  }
  std::mt19937 rng(7);
  for (const Tri* m : {&parts, &crowd}) {
    const MeshSurface s(m->v, m->f, false);
    const Vec3 lo = s.bbox_min() - Vec3::Constant(1), hi = s.bbox_max() + Vec3::Constant(1);
    std::uniform_real_distribution<double> u(0, 1);
    for (int q = 0; q < 400; ++q) {
      Vec3 x;
      for (int k = 0; k < 3; ++k) x[k] = lo[k] + (hi[k] - lo[k]) * (q % 2 ? std::pow(u(rng), 8) : u(rng));
      const double reach = q % 3 == 0 ? 0.05 : 1.5 * u(rng);
      std::vector<std::uint32_t> got, want;
      s.near(x, reach, got);
      for (std::size_t t = 0; t < m->f.size(); ++t) {
        const auto& f = m->f[t];
        const auto tp = contact::closest_point_on_triangle(x, m->v[f[0]], m->v[f[1]], m->v[f[2]]);
        if ((x - tp.point).norm() < reach) want.push_back(static_cast<std::uint32_t>(t));
      }
      EXPECT_EQ(got, want) << "query " << q << " at " << x.transpose() << ", reach " << reach;
    }
  }
}

TEST(MeshSurfaceSearch, DeepItemsGiveTheContactsOfUnmarkedOnesWithinTheSkin) {
  // A wall's near list marks a triangle deep when the sphere's centre is
  // over its face by more than the skin from each edge's line: until the
  // next build (each grain moves less than the skin) sphere_screen takes
  // such a triangle's face without testing its edges. Spheres listed at
  // random places, then moved by just under the skin in random directions
  // and straight towards the rims: the contacts from the marked list are
  // those of the plain one, bit for bit. Meshes with rims and ridges, where
  // a face taken wrongly would replace an edge or vertex contact (marking
  // every item over its face fails here), and a fine flat grid; two-sided
  // and one-sided. A list of one marked item skips the screen (its plane
  // alone decides): spheres behind a one-sided face, beyond r of its plane
  // and just within it are among those compared.
  Tri box = grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 1, 1);  // open box: rims and concave edges
  box.add(grid(Vec3(0, 0, 0), Vec3(0, 0, 0.6), Vec3(1, 0, 0), 1, 1));
  box.add(grid(Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0.6), 1, 1));
  Tri ridge = grid(Vec3(0, 0, 0), Vec3(0.5, 0, 0.2), Vec3(0, 1, 0), 2, 2);  // a convex ridge at x = 0.5
  ridge.add(grid(Vec3(0.5, 0, 0.2), Vec3(0.5, 0, -0.2), Vec3(0, 1, 0), 2, 2));
  const Tri fine = grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 8, 8);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.2, 1.2), z(-0.25, 0.3), rad(0.02, 0.15), sk(0.005, 0.06), dir(-1, 1);
  std::size_t marked_total = 0, compared = 0, lone = 0;
  const Tri* const meshes[] = {&box, &ridge, &fine};
  for (int run = 0; run < 6; ++run) {  // each mesh two-sided, then one-sided
    const auto s = surface(*meshes[run % 3], run >= 3);
    for (int q = 0; q < 3000; ++q) {
      const Vec3 x0(u(rng), u(rng), z(rng));
      const double r = rad(rng), skin = sk(rng);
      std::vector<std::uint32_t> marked, plain;
      s.near(x0, r + skin, marked, nullptr, skin);
      s.near(x0, r + skin, plain);
      ASSERT_EQ(marked.size(), plain.size());
      std::size_t deep = 0;
      for (std::size_t k = 0; k < marked.size(); ++k) {
        ASSERT_EQ(marked[k] & MeshSurface::kTriangle, plain[k]);
        deep += (marked[k] & MeshSurface::kDeep) != 0;
      }
      marked_total += deep;
      if (deep == 0) continue;
      lone += marked.size() == 1;
      std::vector<Vec3> moves;
      for (int k = 0; k < 6; ++k) {
        Vec3 d(dir(rng), dir(rng), dir(rng));
        moves.push_back(skin * 0.999999 * d.normalized());
      }
      for (const auto& rim : {Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 1, 0)})
        moves.push_back(skin * 0.999999 * rim);
      for (const auto& d : moves) {
        const Vec3 x = x0 + d;
        MeshContact a[16], b[16];
        const int na = s.sphere_contacts(x, r, marked, a, 16), nb = s.sphere_contacts(x, r, plain, b, 16);
        ASSERT_EQ(na, nb) << "built at " << x0.transpose() << ", r " << r << ", skin " << skin << ", at " << x.transpose();
        for (int k = 0; k < std::min(na, 16); ++k) {
          EXPECT_EQ(a[k].point, b[k].point);
          EXPECT_EQ(a[k].normal, b[k].normal);
          EXPECT_EQ(a[k].depth, b[k].depth);
          EXPECT_EQ(a[k].triangle, b[k].triangle);
          EXPECT_EQ(a[k].feature, b[k].feature);
        }
        compared += static_cast<std::size_t>(na);
      }
    }
  }
  EXPECT_GT(marked_total, 1000u);  // the marking is there to be tested
  EXPECT_GT(compared, 1000u);
  EXPECT_GT(lone, 500u);  // and lists of one marked item
}

TEST(MeshSurfaceSphere, PlanesSettleWhatTheyCanAsTheFullRuleDoes) {
  // resolve_sphere first tries the triangles' planes (resolve_by_planes):
  // the centre over one or more faces, every other triangle within reach
  // across an edge shared with one of them. What it settles must be the full
  // rule's contacts bit for bit, on meshes where the shortcut would be wrong
  // if it took too much: rims, convex ridges and corners, concave valleys
  // and corners, a bumpy surface, obtuse slivers, a pyramid's apex; listed
  // plain and marked (deep items), two-sided and one-sided.
  Tri box = open_box(Vec3(0, 0, 0), Vec3(1, 1, 0.6));
  box.weld();
  Tri bumpy = grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 5, 5);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> bump(-0.06, 0.06);
  for (auto& v : bumpy.v) v.z() += bump(rng);
  Tri slivers = grid(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 1, 7);  // cells 7 times wider than deep
  for (auto& v : slivers.v) v.x() += 0.3 * v.y();                           // sheared: obtuse corners
  Tri pyramid;
  pyramid.v = {Vec3(0.5, 0.5, 0.3), Vec3(1, 0.5, 0), Vec3(0.5, 1, 0), Vec3(0, 0.5, 0), Vec3(0.5, 0, 0)};
  pyramid.f = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
  Tri ridge = folded(-0.4, 3), valley = folded(0.6, 3);
  for (auto* m : {&ridge, &valley})
    for (auto& v : m->v) v = Vec3(0.5 * (v.x() + 1), 0.5 * (v.y() + 1), v.z());
  std::uniform_real_distribution<double> u(-0.15, 1.15), z(-0.2, 0.35), rad(0.03, 0.2), sk(0.0, 0.05);
  std::size_t settled = 0, ruled = 0, several = 0;
  const std::array<const Tri*, 6> meshes{&box, &bumpy, &slivers, &pyramid, &ridge, &valley};
  for (std::size_t c = 0; c < 2 * meshes.size(); ++c) {
    const auto s = surface(*meshes[c / 2], c % 2 == 1);  // two-sided, then one-sided
    for (int q = 0; q < 10000; ++q) {
      const Vec3 x(u(rng), u(rng), z(rng));
      const double r = rad(rng), skin = sk(rng);
      std::vector<std::uint32_t> plain, marked;
      s.near(x, r, plain);
      s.near(x, r + skin, marked, nullptr, skin);
      for (const auto* tris : {&plain, &marked}) {
        MeshContact a[16], b[16];
        const int na = s.resolve_by_planes(x, r, *tris, a, 16);
        if (na < 0) {
          ++ruled;
          continue;
        }
        const int nb = s.resolve_rule(x, r, *tris, b, 16);
        ASSERT_EQ(na, nb) << "at " << x.transpose() << ", r " << r;
        for (int k = 0; k < na; ++k) {
          EXPECT_EQ(a[k].point, b[k].point);
          EXPECT_EQ(a[k].normal, b[k].normal);
          EXPECT_EQ(a[k].depth, b[k].depth);
          EXPECT_EQ(a[k].triangle, b[k].triangle);
          EXPECT_EQ(a[k].feature, 0);
        }
        settled += na > 0;
        several += na > 1;
        MeshContact c[16];  // resolve_sphere takes them
        ASSERT_EQ(s.resolve_sphere(x, r, *tris, c, 16), na);
      }
    }
  }
  // Each way taken often: the shortcut (one face, several), and the full rule.
  EXPECT_GT(settled, 20000u);
  EXPECT_GT(several, 2000u);
  EXPECT_GT(ruled, 20000u);
}

}  // namespace
}  // namespace grains::test

namespace grains::test {
namespace {

TEST(MeshWall, SpinningDrumUnderArkodeKeepsItsBed) {
  // The adaptive integrator places the rotating mesh at each stage's time;
  // the contact normals of the slots are written while it evaluates. The
  // bed stays in the drum and is dragged up as under Verlet.
  const fs::path off = scratch("drum_arkode.off");
  write_off(off, drum(Vec3(0, 0, 0), 0.01, 0.006, 48, 3));
  std::string text = drum_case(off, ", axis: [0, 1, 0], angular_velocity: 40, start: 0.005, ramp: 0.005", 0.045);
  text.replace(text.find("time: {dt: 1e-5"), std::string("time: {dt: 1e-5").size(), "time: {integrator: arkode, dt: 1e-5");
  // The same bed under ARKODE and under Verlet: dragged the same way, about as far.
  auto drag = [&](const std::string& t) {
    auto s = from_yaml(t);
    s.pipeline.initialize(s.scene);
    const auto& p = s.scene.particles;
    auto mean_x = [&] {
      double c = 0;
      for (std::size_t i = 0; i < p.n_owned(); ++i) c += p.x[i].x();
      return c / static_cast<double>(p.n_owned());
    };
    const double x0 = mean_x();
    while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
    EXPECT_EQ(p.n_owned(), 150u);
    for (std::size_t i = 0; i < p.n_owned(); ++i) {
      EXPECT_TRUE(p.x[i].allFinite());
      EXPECT_LT(std::hypot(p.x[i].x(), p.x[i].z()), 0.01);
    }
    return mean_x() - x0;
  };
  const double arkode = drag(text);
  text.replace(text.find("time: {integrator: arkode, dt: 1e-5"), std::string("time: {integrator: arkode, dt: 1e-5").size(),
               "time: {dt: 1e-5");
  const double verlet = drag(text);
  std::cout << "bed dragged by " << arkode << " m (ARKODE), " << verlet << " m (Verlet)\n";
  EXPECT_LT(verlet, -5e-5);
  EXPECT_LT(arkode, -5e-5);
  EXPECT_NEAR(arkode, verlet, 0.3 * std::abs(verlet));
}

}  // namespace
}  // namespace grains::test
