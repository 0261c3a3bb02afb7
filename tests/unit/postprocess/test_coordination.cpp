// Contacts and coordination numbers of configurations whose contacts are
// known by construction; rattler rules; wall contacts; ellipsoid contacts.
#include <gtest/gtest.h>

#include <cmath>

#include "postprocess/contacts.hpp"
#include "postprocess/walls.hpp"

#include <filesystem>
#include <string>

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

namespace grains::postprocess {
namespace {

Frame spheres(const std::vector<Vec3>& x, double r) {
  Frame f;
  f.x = x;
  f.radius.assign(x.size(), r);
  for (std::size_t i = 0; i < x.size(); ++i) f.id.push_back(static_cast<std::int64_t>(i));
  return f;
}

const Box kAll{Vec3::Constant(-1e9), Vec3::Constant(1e9)};

TEST(Coordination, FccClusterInteriorHasTwelve) {
  // FCC with nearest-neighbour distance 1; spheres of radius 0.5005 overlap
  // their 12 nearest neighbours by 1e-3 and nothing else (next shell at sqrt 2).
  const double a = std::sqrt(2.0);
  std::vector<Vec3> x;
  const Vec3 basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k)
        for (const auto& b : basis) x.push_back(a * (Vec3(i, j, k) + b));
  const Frame f = spheres(x, 0.5005);
  const auto c = find_contacts(f);
  for (const auto& k : c) {
    EXPECT_NEAR(k.overlap, 1e-3, 1e-12);
    EXPECT_NEAR(k.radius, 0.25025, 1e-12);
    EXPECT_NEAR((f.x[k.i] - f.x[k.j]).normalized().dot(k.normal), 1.0, 1e-12);
  }
  // Interior: centres at least one cell from the cluster's faces.
  const Box inner{Vec3::Constant(a - 1e-9), Vec3::Constant(3 * a + 1e-9)};
  const auto z = coordination(f, units_of(f), c, inner);
  ASSERT_GT(z.n_selected, 50u);
  EXPECT_DOUBLE_EQ(z.mean_z, 12.0);
  EXPECT_DOUBLE_EQ(z.mean_z_without_rattlers, 12.0);
  EXPECT_EQ(z.n_rattlers, 0u);
  ASSERT_EQ(z.histogram.size(), 13u);
  EXPECT_EQ(z.histogram[12], z.n_selected);
  // Total contacts: 500 spheres; every pair at distance 1 counted once.
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size(); ++j)
      if ((x[i] - x[j]).norm() < 1.001) ++pairs;
  EXPECT_EQ(c.size(), pairs);
}

TEST(Coordination, GapCountsNearContactsOnly) {
  const Frame f = spheres({Vec3(0, 0, 0), Vec3(1.01, 0, 0), Vec3(0, 1.2, 0)}, 0.5);
  EXPECT_EQ(find_contacts(f).size(), 0u);
  ContactOptions o;
  o.gap = 0.02;
  const auto c = find_contacts(f, o);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].overlap, -0.01, 1e-12);
}

TEST(Coordination, RattlerRulesOnceAndIterative) {
  // A 3x3x3 simple-cubic block of touching spheres (z = 3 at corners, 4 on
  // edges, 5 on faces, 6 inside) plus one sphere hanging off a corner.
  std::vector<Vec3> x;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) x.emplace_back(i, j, k);
  x.emplace_back(-1, 0, 0);  // touches the corner (0,0,0) only
  const Frame f = spheres(x, 0.5005);
  const auto c = find_contacts(f);
  EXPECT_EQ(c.size(), 54u + 1u);  // 3 directions x 18 bonds, plus the hanger
  const Units u = units_of(f);
  // Once: rattlers are 7 corners (z = 3) and the hanger (z = 1); the corner
  // touching the hanger has z = 4 and stays.
  const auto once = coordination(f, u, c, kAll, 4, RattlerRule::once);
  EXPECT_EQ(once.n_rattlers, 8u);
  EXPECT_EQ(once.z[0], 4);
  EXPECT_EQ(once.rattler[0], 0);
  EXPECT_EQ(once.rattler[27], 1);
  EXPECT_NEAR(once.mean_z, (8 * 3 + 12 * 4 + 6 * 5 + 6 + 1 + 1) / 28.0, 1e-12);
  // Iterative: removing the hanger drops the corner (0,0,0) to 3; removing
  // corners drops edge centres (z = 4, two corner neighbours) to 2, and so on:
  // the cubic block has no 4-core at all.
  const auto it = coordination(f, u, c, kAll, 4, RattlerRule::iterative);
  EXPECT_EQ(it.n_rattlers, 28u);
  EXPECT_EQ(it.mean_z_without_rattlers, 0.0);
  // With threshold 3 the block is its own 3-core except the hanger.
  const auto three = coordination(f, u, c, kAll, 3, RattlerRule::iterative);
  EXPECT_EQ(three.n_rattlers, 1u);
  EXPECT_EQ(three.rattler[27], 1);
  EXPECT_EQ(three.z_rigid[0], 3);
}

TEST(Coordination, WallContactsCount) {
  // Three spheres on a floor at z = 0, one of them also against a wall at x = 0.
  const Frame f = spheres({Vec3(0.4999, 2, 0.4999), Vec3(3, 2, 0.4999), Vec3(3, 2, 0.6)}, 0.5);
  WallSet w;
  sim::PlaneWall floor, side;
  side.normal = Vec3(1, 0, 0);
  w.add(floor);
  w.add(side);
  const auto wz = wall_contacts(f, w);
  EXPECT_EQ(wz, (std::vector<int>{2, 1, 0}));
  sim::CylinderWall cy;
  cy.surface = {Vec3(0, 2, 0), Vec3(0, 0, 1), 3.4999, 0, 1, true};
  w = {};
  w.add(cy);
  // Spheres 1 and 2 sit 0.4999 inside the cylinder's surface (t = 0.5, 0.6 within
  // its length); sphere 0 is 3 away from it.
  EXPECT_EQ(wall_contacts(f, w), (std::vector<int>{0, 1, 1}));
  w.of<sim::CylinderWall>()[0].surface.t_max = 0.55;  // sphere 2's centre now beyond the cylinder's end
  EXPECT_EQ(wall_contacts(f, w), (std::vector<int>{0, 1, 0}));
}

TEST(Coordination, ClumpBallsCountOncePerClumpPair) {
  // Two dimers side by side: each ball of dimer A touches one ball of dimer B.
  Frame f = spheres({Vec3(0, 0, 0), Vec3(0.8, 0, 0), Vec3(0, 0.999, 0), Vec3(0.8, 0.999, 0)}, 0.5);
  f.body = {7, 7, 9, 9};
  const auto c = find_contacts(f);
  EXPECT_EQ(c.size(), 2u);  // ball-ball contacts between the clumps; none inside a clump
  const Units u = units_of(f);
  ASSERT_EQ(u.count, 2u);
  EXPECT_NEAR(u.centre[0].x(), 0.4, 1e-12);
  const auto z = coordination(f, u, c, kAll, 1);
  EXPECT_EQ(z.z, (std::vector<int>{1, 1}));
}

TEST(Coordination, EllipsoidContactsFollowOrientation) {
  // Two prolate spheroids (2, 1, 1) end to end 3.9 apart along x overlap by
  // 0.1; turning the second by 90 degrees about z separates them (2 + 1 < 3.9).
  Frame f;
  f.x = {Vec3(0, 0, 0), Vec3(3.9, 0, 0)};
  f.radius = {1, 1};
  f.semi_axes = {Vec3(2, 1, 1), Vec3(2, 1, 1)};
  f.orientation = {Quat::Identity(), Quat::Identity()};
  auto c = find_contacts(f);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].overlap, 0.1, 1e-6);
  f.orientation[1] = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
  EXPECT_TRUE(find_contacts(f).empty());
}

// A walls file whose records this build cannot rebuild: a kind it does not
// know (a newer grains) or a record of the wrong length: a clear error naming
// the file, the wall and what is wrong.
TEST(Coordination, WallRecordsThatCannotBeRebuiltAreReported) {
  const auto dir = std::filesystem::temp_directory_path() / "grains_wall_records";
  std::filesystem::create_directories(dir);
  auto write = [&](const std::string& name, int values) {
    vtkNew<vtkPolyData> poly;
    vtkNew<vtkDoubleArray> r;
    r->SetName(name.c_str());
    for (int k = 0; k < values; ++k) r->InsertNextValue(k == 5 ? 1.0 : 0.0);
    poly->GetFieldData()->AddArray(r);
    const auto file = dir / (name + ".vtp");
    vtkNew<vtkXMLPolyDataWriter> w;
    w->SetInputData(poly);
    w->SetFileName(file.c_str());
    w->Write();
    return file;
  };
  auto message = [](const std::filesystem::path& f) {
    try {
      (void)read_walls(f);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const auto m1 = message(write("wall_0_teapot", 8));
  EXPECT_NE(m1.find("wall 0 is of kind 'teapot', which this grains does not know"), std::string::npos) << m1;
  const auto m2 = message(write("wall_3_plane", 5));
  EXPECT_NE(m2.find("wall 3 (plane): malformed record of 5 numbers"), std::string::npos) << m2;
  // A plane record of the right length rebuilds the plane.
  EXPECT_EQ(read_walls(write("wall_0_plane", 8)).of<sim::PlaneWall>().size(), 1u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace grains::postprocess
