// End to end: a tiny pour run through the library (io::make_simulation,
// io::run), then the postprocess library, `grains analyze` and `grains render`
// on its output folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "io/case/case.hpp"
#include "io/cli/analyze_command.hpp"
#include "io/run/simulation.hpp"
#include "postprocess/analysis.hpp"
#include "postprocess/render.hpp"

namespace grains::postprocess {
namespace {

namespace fs = std::filesystem;

// 300 spheres (d = 1 mm) poured into a 6 d x 6 d box.
const char* kCase = R"(title: tiny_pour
domain: {min: [-0.001, -0.001, -0.001], max: [0.007, 0.007, 0.036]}
gravity: [0, 0, -9.81]
materials:
  - {name: grain, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.3, friction: 0.5, rolling_friction: 0.0}
particles:
  - name: spheres
    material: grain
    radius: 0.0005
    count: 300
    placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.006, 0.006, 0.035]}, seed: 11}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain}
  - {type: plane, name: x0, point: [0, 0, 0], normal: [1, 0, 0], material: grain}
  - {type: plane, name: x1, point: [0.006, 0, 0], normal: [-1, 0, 0], material: grain}
  - {type: plane, name: y0, point: [0, 0, 0], normal: [0, 1, 0], material: grain}
  - {type: plane, name: y1, point: [0, 0.006, 0], normal: [0, -1, 0], material: grain}
time: {dt: 8.654e-6, end: 0.2}
neighbor: {skin: 0.1}
output: {every: 0.05}
)";

class AnalyzeRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("grains_pp_test_" + std::to_string(getpid()));
    fs::create_directories(dir_);
    std::ofstream(dir_ / "case.yaml") << kCase;
    auto sim = io::make_simulation(io::load_case((dir_ / "case.yaml").string(), {}));
    io::RunOptions o;
    o.out_dir = dir_ / "out";
    o.quiet = true;
    io::run(sim, o);
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  static fs::path dir_;
};
fs::path AnalyzeRun::dir_;

TEST_F(AnalyzeRun, FramesAndContactsMatchTheSimulation) {
  const auto frames = list_frames(dir_ / "out");
  ASSERT_EQ(frames.size(), 5u);  // t = 0, 0.05, ..., 0.2
  EXPECT_NEAR(frames.back().time, 0.2, 8.654e-6);  // within a step
  const Frame f = read_frame(dir_ / "out");
  EXPECT_EQ(f.index, 4u);
  ASSERT_EQ(f.size(), 300u);
  EXPECT_FALSE(f.has_orientation());
  EXPECT_EQ(read_frame_at_time(dir_ / "out", 0.06).index, 1u);
  // Contacts recomputed from positions and radii reproduce the run's own
  // per-particle coordination output exactly.
  const auto c = find_contacts(f);
  std::vector<int> z(f.size(), 0);
  for (const auto& k : c) {
    ++z[k.i];
    ++z[k.j];
  }
  ASSERT_EQ(f.coordination.size(), f.size());
  EXPECT_EQ(z, f.coordination);
  // Settled bed: every particle touches something (a wall or a particle).
  const auto walls = read_walls(walls_file(dir_ / "out", f.index));
  EXPECT_EQ(walls.of<sim::PlaneWall>().size(), 5u);
  const auto wz = wall_contacts(f, walls);
  for (std::size_t i = 0; i < f.size(); ++i) EXPECT_GT(z[i] + wz[i], 0) << "particle " << i;
}

TEST_F(AnalyzeRun, AnalysisOfTheSettledBed) {
  const Frame f = read_frame(dir_ / "out");
  const auto walls = read_walls(walls_file(dir_ / "out", f.index));
  AnalysisOptions o;
  o.margin_diameters = 1.0;
  const auto r = analyze_frame(f, o, &walls);
  EXPECT_TRUE(r.packing.exact);
  // A loose-to-random frictional bed (REFERENCES.md: 0.55-0.60 in the bulk; a
  // 6 d box has wall-dominated layering, hence the wider band).
  EXPECT_GT(r.packing.phi, 0.50);
  EXPECT_LT(r.packing.phi, 0.66);
  EXPECT_GT(r.coordination.n_selected, 20u);
  EXPECT_GT(r.coordination.mean_z, 3.0);
  EXPECT_LT(r.coordination.mean_z, 7.0);
  // Non-rattlers keep at least... their contacts with other non-rattlers and walls: positive.
  EXPECT_GT(r.coordination.mean_z_without_rattlers, 2.0);
  EXPECT_GT(r.forces.n_contacts, 20u);
  EXPECT_GT(r.forces.mean_relative_overlap, 0.0);
  EXPECT_LT(r.forces.mean_relative_overlap, 0.02);
  // P(f/<f>) integrates to (almost) one: contacts beyond 6 <f> are rare.
  double area = 0;
  for (double p : r.forces.pdf) area += p * r.forces.bin;
  EXPECT_GT(area, 0.97);
  EXPECT_LE(area, 1.0 + 1e-12);
  // Profile from the floor to the top of the highest sphere: dense inside the
  // bed, sparse in the top slab (it holds only the caps of the highest spheres).
  ASSERT_GT(r.profile.phi.size(), 10u);
  EXPECT_GT(*std::max_element(r.profile.phi.begin(), r.profile.phi.end()), 0.55);
  EXPECT_LT(r.profile.phi.back(), 0.2);
  EXPECT_NEAR(r.profile.lo.front(), 0.0, 1e-5);  // the floor
}

TEST_F(AnalyzeRun, AnalyzeCommandWritesFiles) {
  std::ostringstream out, err;
  const fs::path dest = dir_ / "analysis";
  const int rc = io::run_analyze_command({(dir_ / "out").string(), "--frame", "-1", "--region",
                                          "0.001,0.001,0.001,0.005,0.005,0.006", "-o", dest.string()},
                                         out, err);
  ASSERT_EQ(rc, 0) << err.str();
  for (const char* name : {"analysis.json", "phi_profile.csv", "rdf.csv", "coordination.csv", "contact_forces.csv",
                           "contacts.csv"})
    EXPECT_TRUE(fs::exists(dest / name)) << name;
  std::ifstream j(dest / "analysis.json");
  std::stringstream text;
  text << j.rdbuf();
  EXPECT_NE(text.str().find("\"automatic\": false"), std::string::npos);
  EXPECT_NE(text.str().find("\"walls_counted\": true"), std::string::npos);
  EXPECT_NE(out.str().find("packing fraction"), std::string::npos);
  // Plots through python3-matplotlib.
  EXPECT_TRUE(fs::exists(dest / "phi_profile.png")) << err.str();
  EXPECT_TRUE(fs::exists(dest / "rdf.png")) << err.str();
  // Bad input: exit status 2 and a message.
  std::ostringstream o2, e2;
  EXPECT_EQ(io::run_analyze_command({(dir_ / "out").string(), "--region", "1,2,3"}, o2, e2), 2);
  EXPECT_NE(e2.str().find("six numbers"), std::string::npos);
  EXPECT_EQ(io::run_analyze_command({(dir_ / "out").string(), "--frame", "99"}, o2, e2), 2);
  EXPECT_NE(e2.str().find("has 5 frames"), std::string::npos);
  EXPECT_EQ(io::run_analyze_command({(dir_ / "nowhere").string()}, o2, e2), 2);
}

TEST_F(AnalyzeRun, RenderIsNotBlank) {
  const fs::path png = dir_ / "snap.png";
  RenderOptions o;
  o.width = 320;
  o.height = 240;
  o.color = "velocity:z";
  render_frame(dir_ / "out", -1, o, png);
  const auto s = png_statistics(png);
  EXPECT_EQ(s.width, 320);
  EXPECT_EQ(s.height, 240);
  // A blank (single-colour) image has variance 0; spheres shaded over the
  // background and a colour bar give many colours and a large spread.
  EXPECT_GT(s.variance, 200.0);
  EXPECT_GT(s.distinct_colours, 200u);
  // The command: unknown field is an error that lists the fields.
  std::ostringstream out, err;
  EXPECT_EQ(io::run_render_command({(dir_ / "out").string(), "--color", "temperature", "-o", png.string()}, out, err),
            1);
  EXPECT_NE(err.str().find("radius"), std::string::npos);
  EXPECT_EQ(io::run_render_command({(dir_ / "out").string()}, out, err), 2);  // no -o
}

TEST_F(AnalyzeRun, RenderWithAStaleDisplayStartsItsOwn) {
  // A DISPLAY that cannot be opened (e.g. left over from an ssh session)
  // made VTK abort the process; the renderer now starts its own Xvfb, and
  // gives the caller's DISPLAY back afterwards.
  const char* before = std::getenv("DISPLAY");
  const std::string saved = before ? before : "";
  setenv("DISPLAY", ":987654", 1);
  const fs::path png = dir_ / "stale.png";
  RenderOptions o;
  o.width = 160;
  o.height = 120;
  EXPECT_NO_THROW(render_frame(dir_ / "out", -1, o, png));
  EXPECT_TRUE(fs::exists(png));
  EXPECT_STREQ(std::getenv("DISPLAY"), ":987654");
  if (before)
    setenv("DISPLAY", saved.c_str(), 1);
  else
    unsetenv("DISPLAY");
}

}  // namespace
}  // namespace grains::postprocess
