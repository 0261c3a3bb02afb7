// Readers: every format gives the same cube, and every broken file gives its
// documented MeshError kind with a message that says what and where.

#include "io/mesh/mesh_error.hpp"
#include "io/mesh/mesh_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace grains::mesh;

namespace {

std::string data(const std::string& name) { return std::string(GRAINS_SOURCE_DIR) + "/tests/data/meshes/" + name; }

// Runs f, expects a MeshError of `kind` whose message contains every fragment.
template <class F>
void expect_error(F&& f, MeshErrorKind kind, std::initializer_list<std::string> fragments) {
  try {
    f();
    FAIL() << "expected MeshError " << to_string(kind);
  } catch (const MeshError& e) {
    EXPECT_EQ(e.kind(), kind) << e.what();
    for (const auto& s : fragments) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << "'" << s << "' not in: " << e.what();
  }
}

std::string temp_file(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("grains_test_mesh_" + name);
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

}  // namespace

TEST(MeshReaders, CubeIsTheSameInEveryFormat) {
  for (const char* name : {"cube.off", "cube_ascii.stl", "cube_binary.stl", "cube_binary_solid_header.stl"}) {
    SCOPED_TRACE(name);
    const TriangleMesh m = load_mesh(data(name));
    EXPECT_EQ(m.vertices.size(), 8u);
    EXPECT_EQ(m.faces.size(), 12u);
    EXPECT_NEAR(m.signed_volume(), 8.0, 1e-12);
    EXPECT_NEAR(m.surface_area(), 24.0, 1e-12);
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
  }
}

TEST(MeshReaders, ObjQuadsAndNegativeIndices) {
  const TriangleMesh m = load_mesh(data("cube_quads.obj"));
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.faces.size(), 12u);  // six quads, fan-triangulated
  EXPECT_NEAR(m.signed_volume(), 1.0, 1e-12);
  EXPECT_TRUE(m.warnings.empty());
}

TEST(MeshReaders, BunnyLoads) {
  const TriangleMesh m = load_mesh(data("bunny00.off"));
  EXPECT_EQ(m.vertices.size(), 37706u);
  EXPECT_EQ(m.faces.size(), 75408u);
  EXPECT_NEAR(m.signed_volume(), 0.1992, 5e-4);
  EXPECT_TRUE(m.warnings.empty());
}

TEST(MeshReaders, TruncatedBinaryStl) {
  expect_error([] { read_stl(data("truncated.stl")); }, MeshErrorKind::truncated,
               {"truncated.stl", "12 triangles", "5 complete triangles"});
}

TEST(MeshReaders, StlShorterThanHeader) {
  const auto p = temp_file("short.stl", std::string(40, '\x01'));
  expect_error([&] { read_stl(p); }, MeshErrorKind::truncated, {"84-byte header"});
}

TEST(MeshReaders, EmptyFiles) {
  expect_error([] { read_mesh(data("empty.stl")); }, MeshErrorKind::empty, {"empty.stl", "0 bytes"});
  expect_error([] { read_mesh(data("empty.off")); }, MeshErrorKind::empty, {"empty.off"});
  const auto p = temp_file("nofaces.obj", "# only vertices\nv 0 0 0\nv 1 0 0\n");
  expect_error([&] { read_obj(p); }, MeshErrorKind::empty, {"no faces"});
}

TEST(MeshReaders, NanCoordinateNamesTheLine) {
  expect_error([] { read_off(data("nan_vertex.off")); }, MeshErrorKind::non_finite, {"nan_vertex.off:5:", "nan"});
  const auto p = temp_file("inf.obj", "v 0 0 0\nv 1 0 inf\nv 0 1 0\nf 1 2 3\n");
  expect_error([&] { read_obj(p); }, MeshErrorKind::non_finite, {":2:"});
}

TEST(MeshReaders, SyntaxErrorsNameTheLine) {
  const auto off = temp_file("badindex.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
  expect_error([&] { read_off(off); }, MeshErrorKind::parse, {":6:", "out of range 0..2"});
  const auto obj = temp_file("badindex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  expect_error([&] { read_obj(obj); }, MeshErrorKind::parse, {":4:", "1..3"});
  const auto stl = temp_file("bad.stl", "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 zero\n");
  expect_error([&] { read_stl(stl); }, MeshErrorKind::parse, {":4:", "'zero'"});
  const auto off2 = temp_file("short.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n");
  expect_error([&] { read_off(off2); }, MeshErrorKind::parse,
               {":2:", "declares 4 vertices and 4 faces, but only 2 lines follow"});
  // Found by fuzz_mesh_off: a huge declared count used to be reserved before
  // it was checked against the file.
  const auto huge = temp_file("huge.off", "OFF\n488888888882 9\n6  2 19\n 3  1 5 9\n");
  expect_error([&] { read_off(huge); }, MeshErrorKind::parse, {"declares 488888888882 vertices"});
}

TEST(MeshReaders, UnknownFormatAndMissingFile) {
  expect_error([] { read_mesh("shape.ply"); }, MeshErrorKind::unknown_format, {".stl, .obj and .off"});
  expect_error([] { read_mesh(data("does_not_exist.off")); }, MeshErrorKind::cannot_open, {"does_not_exist.off"});
}

TEST(MeshReaders, PolyhedronMomentsOfTheCube) {
  const PolyhedronMoments pm = polyhedron_moments(load_mesh(data("cube.off")));
  EXPECT_NEAR(pm.volume, 8.0, 1e-12);
  EXPECT_NEAR(pm.centroid.norm(), 0.0, 1e-12);
  // Cube of side 2, unit density: I = V (a^2 + b^2) / 12 = 8 * 8 / 12.
  EXPECT_NEAR((pm.inertia - Eigen::Matrix3d::Identity() * 16.0 / 3.0).norm(), 0.0, 1e-12);
}

TEST(MeshReaders, PolyhedronMomentsOfTheReferenceTetrahedron) {
  const PolyhedronMoments pm = polyhedron_moments(load_mesh(data("reference_tetrahedron.off")));
  EXPECT_NEAR(pm.volume, 1.0 / 6.0, 1e-12);
  EXPECT_NEAR((pm.centroid - Eigen::Vector3d::Constant(0.25)).norm(), 0.0, 1e-12);
  // Unit right tetrahedron about its centroid: I_xx = 1/80, I_xy = 1/480.
  EXPECT_NEAR(pm.inertia(0, 0), 1.0 / 80.0, 1e-12);
  EXPECT_NEAR(pm.inertia(0, 1), 1.0 / 480.0, 1e-12);
}
