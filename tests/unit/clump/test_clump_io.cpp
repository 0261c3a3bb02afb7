// Clump YAML files and the `grains clump` command.

#include "clump_test_data.hpp"
#include "io/cli/clump_command.hpp"
#include "contact/clump/clump_yaml.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace grains::clump;
using grains::io::run_clump_command;

namespace {
std::string temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("grains_test_clump_" + name)).string();
}
}  // namespace

TEST(ClumpYaml, RoundTrip) {
  ClumpOptions opt;
  opt.decomposition.grid = 16;
  const ClumpTemplate c = build_clump(test_mesh("star.off"), opt);
  const std::string p = temp("star.yaml");
  write_clump_yaml(c, p);
  const ClumpTemplate r = load_clump_yaml(p);
  ASSERT_EQ(r.balls.size(), c.balls.size());
  for (size_t i = 0; i < c.balls.size(); ++i) {
    EXPECT_EQ(r.balls[i].center, c.balls[i].center);
    EXPECT_EQ(r.balls[i].radius, c.balls[i].radius);
  }
  EXPECT_EQ(r.mass, c.mass);
  EXPECT_EQ(r.inertia, c.inertia);
  EXPECT_EQ(r.axes, c.axes);
  EXPECT_EQ(r.centre_of_mass, c.centre_of_mass);
  EXPECT_EQ(r.meta.n1, c.meta.n1);
  EXPECT_EQ(r.meta.n3, c.meta.n3);
  EXPECT_EQ(r.meta.hausdorff, c.meta.hausdorff);
  EXPECT_EQ(r.meta.grid, 16);
}

TEST(ClumpYaml, BadFilesSayWhatAndWhere) {
  const std::string p = temp("bad.yaml");
  std::ofstream(p) << "grains_clump: 1\ndensity: 1000\nmass: 1\nvolume: 0.001\ninertia_principal: [1, 1, 1]\n"
                      "centre_of_mass_mesh_frame: [0, 0, 0]\nbody_axes_mesh_frame: [[1,0,0],[0,1,0],[0,0,1]]\n"
                      "balls:\n  - [0, 0, 0, 0.1]\n  - [0, 0, -0.1]\n";
  try {
    load_clump_yaml(p);
    FAIL();
  } catch (const ClumpFileError& e) {
    EXPECT_NE(std::string(e.what()).find(":10: ball 1 must be [x, y, z, r]"), std::string::npos) << e.what();
  }
  std::ofstream(p) << "density: 1000\n";
  EXPECT_THROW(load_clump_yaml(p), ClumpFileError);
  EXPECT_THROW(load_clump_yaml(temp("missing.yaml")), ClumpFileError);
}

TEST(ClumpCommand, WritesAndPrints) {
  const std::string out_path = temp("cube.yaml");
  std::filesystem::remove(out_path);
  std::ostringstream out, err;
  const int rc = run_clump_command({mesh_path("cube.off"), "--grid", "16", "--mu", "0.25", "-o", out_path}, out, err);
  ASSERT_EQ(rc, 0) << err.str();
  const std::string s = out.str();
  for (const char* part : {"n1 = n2 = ", "n3 = ", "eps = ", "hausdorff", "volume", "error", "time"}) {
    EXPECT_NE(s.find(part), std::string::npos) << part << " missing in:\n" << s;
  }
  const ClumpTemplate c = load_clump_yaml(out_path);
  EXPECT_EQ(c.meta.grid, 16);
  EXPECT_EQ(c.meta.n3, c.balls.size());
}

TEST(ClumpCommand, BadMeshAndBadUsage) {
  std::ostringstream out, err;
  EXPECT_EQ(run_clump_command({mesh_path("open_box.off")}, out, err), 1);
  EXPECT_NE(err.str().find("not closed"), std::string::npos) << err.str();
  std::ostringstream out2, err2;
  EXPECT_EQ(run_clump_command({mesh_path("cube.off"), "--mu", "2"}, out2, err2), 2);
  EXPECT_NE(err2.str().find("--mu must lie in [0, 1]"), std::string::npos) << err2.str();
  std::ostringstream out3, err3;
  EXPECT_EQ(run_clump_command({}, out3, err3), 2);
  std::ostringstream out4, err4;
  EXPECT_EQ(run_clump_command({mesh_path("tetrahedron.off"), "--grid", "12", "--no-measure"}, out4, err4), 0);
  EXPECT_NE(err4.str().find("warning:"), std::string::npos);  // inward mesh flipped, said so
}
