// Validation: each bad mesh gives its documented error, and orientation
// problems are repaired with a warning (or refused when repair is off).

#include "io/mesh/mesh_error.hpp"
#include "io/mesh/mesh_reader.hpp"

#include <gtest/gtest.h>

using namespace grains::mesh;

namespace {

std::string data(const std::string& name) { return std::string(GRAINS_SOURCE_DIR) + "/tests/data/meshes/" + name; }

MeshError error_of(const std::string& name, ValidationOptions opt = {}) {
  try {
    load_mesh(data(name), opt);
  } catch (const MeshError& e) {
    return e;
  }
  ADD_FAILURE() << name << " was accepted";
  return MeshError(MeshErrorKind::parse, "");
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(MeshValidation, OpenBoxCountsAndLocatesBoundaryEdges) {
  const MeshError e = error_of("open_box.off");
  EXPECT_EQ(e.kind(), MeshErrorKind::not_closed);
  EXPECT_TRUE(contains(e.what(), "open_box.off")) << e.what();
  EXPECT_TRUE(contains(e.what(), "4 boundary edge(s)")) << e.what();
  // The missing face is the top (z = 1): every listed edge midpoint has z = 1.
  EXPECT_TRUE(contains(e.what(), ", 1) (faces")) << e.what();
}

TEST(MeshValidation, MushroomIsOpen) {
  const MeshError e = error_of("mushroom.off");
  EXPECT_EQ(e.kind(), MeshErrorKind::not_closed);
  EXPECT_TRUE(contains(e.what(), "64 boundary edge(s)")) << e.what();
}

TEST(MeshValidation, NonManifoldEdge) {
  const MeshError e = error_of("two_tets_sharing_edge.off");
  EXPECT_EQ(e.kind(), MeshErrorKind::non_manifold);
  EXPECT_TRUE(contains(e.what(), "1 edge(s) shared by more than two faces")) << e.what();
  EXPECT_TRUE(contains(e.what(), "edge 0-1")) << e.what();
}

TEST(MeshValidation, DegenerateFace) {
  const MeshError e = error_of("degenerate_face.off");
  EXPECT_EQ(e.kind(), MeshErrorKind::degenerate_face);
  EXPECT_TRUE(contains(e.what(), "1 degenerate face(s)")) << e.what();
  EXPECT_TRUE(contains(e.what(), "face 12 [0 8 3]")) << e.what();
}

TEST(MeshValidation, RepeatedVertexIsDegenerate) {
  TriangleMesh m;
  m.source = "made-up";
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.faces = {{0, 1, 1}};
  try {
    validate_mesh(m);
    FAIL();
  } catch (const MeshError& e) {
    EXPECT_EQ(e.kind(), MeshErrorKind::degenerate_face);
  }
}

TEST(MeshValidation, InwardTetrahedronIsFlippedWithAWarning) {
  const TriangleMesh raw = read_mesh(data("tetrahedron.off"));
  EXPECT_NEAR(raw.signed_volume(), -1.0 / 6.0, 1e-12);
  const TriangleMesh m = load_mesh(data("tetrahedron.off"));
  EXPECT_NEAR(m.signed_volume(), 1.0 / 6.0, 1e-12);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_TRUE(contains(m.warnings[0], "inward-oriented")) << m.warnings[0];
}

TEST(MeshValidation, InwardIsRefusedWhenRepairIsOff) {
  ValidationOptions strict;
  strict.repair_orientation = false;
  const MeshError e = error_of("tetrahedron.off", strict);
  EXPECT_EQ(e.kind(), MeshErrorKind::bad_orientation);
  EXPECT_TRUE(contains(e.what(), "inward")) << e.what();
}

TEST(MeshValidation, InconsistentFaceIsFlippedWithAWarning) {
  TriangleMesh m = read_mesh(data("cube_one_face_flipped.off"));
  const ValidationReport r = validate_mesh(m);
  EXPECT_EQ(r.faces_flipped_for_consistency, 1);
  EXPECT_EQ(r.components_flipped_inward, 0);
  EXPECT_NEAR(m.signed_volume(), 8.0, 1e-12);
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_TRUE(contains(m.warnings[0], "1 face(s) were wound against their neighbours")) << m.warnings[0];
}

TEST(MeshValidation, InconsistentIsRefusedWhenRepairIsOff) {
  ValidationOptions strict;
  strict.repair_orientation = false;
  const MeshError e = error_of("cube_one_face_flipped.off", strict);
  EXPECT_EQ(e.kind(), MeshErrorKind::bad_orientation);
  EXPECT_TRUE(contains(e.what(), "first: face 4")) << e.what();
}

TEST(MeshValidation, WhollyInvertedCubeIsOneInwardComponent) {
  TriangleMesh m = read_mesh(data("cube.off"));
  for (auto& f : m.faces) std::swap(f[1], f[2]);
  const ValidationReport r = validate_mesh(m);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.faces_flipped_for_consistency, 0);
  EXPECT_EQ(r.components_flipped_inward, 1);
  EXPECT_NEAR(m.signed_volume(), 8.0, 1e-12);
}

TEST(MeshValidation, NonFiniteVertexInAMeshBuiltInCode) {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, std::numeric_limits<double>::quiet_NaN(), 0}};
  m.faces = {{0, 1, 2}};
  try {
    validate_mesh(m);
    FAIL();
  } catch (const MeshError& e) {
    EXPECT_EQ(e.kind(), MeshErrorKind::non_finite);
    EXPECT_TRUE(contains(e.what(), "vertex 2"));
  }
}

TEST(MeshValidation, GoodMeshesPassUntouched) {
  for (const char* name : {"cube.off", "sphere.off", "reference_tetrahedron.off", "cow.off", "star.off"}) {
    SCOPED_TRACE(name);
    const TriangleMesh m = load_mesh(data(name));
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
    EXPECT_GT(m.signed_volume(), 0.0);
  }
}
