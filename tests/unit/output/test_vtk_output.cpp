// A run's output can be read back by VTK: the .pvd index lists every frame,
// each frame carries the documented arrays, and summary.json exists.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "sim/laws/sphere_lanes.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test {
namespace {

namespace fs = std::filesystem;

// A small bed poured on a floor, for the figures of summary.json; `extra`
// adds case keys.
std::string small_bed(const std::string& extra = "") {
  return R"(
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.02]}
gravity: [0, 0, -9.81]
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, friction: 0.3}
particles:
  - {material: m, radius: 0.0005, count: 200, placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.02]}}}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}
time: {dt_rayleigh: 0.2, end: 0.002}
output: {every_steps: 40, progress: false, vtk: false}
)" + extra;
}

// Runs the case in a folder of its own and returns its summary.json.
std::string run_summary(const std::string& yaml, const std::string& folder) {
  auto s = from_yaml(yaml);
  const fs::path dir = fs::temp_directory_path() / folder;
  run_into(s, dir);
  std::ifstream in(dir / "summary.json");
  std::stringstream ss;
  ss << in.rdbuf();
  fs::remove_all(dir);
  return ss.str();
}

// The number after "key": in the summary; -1 when the key is absent.
double json_number(const std::string& j, const std::string& key) {
  const auto at = j.find("\"" + key + "\": ");
  return at == std::string::npos ? -1.0 : std::stod(j.substr(at + key.size() + 4));
}

TEST(VtkOutput, FramesAndSeriesReadBack) {
  const std::string yaml = R"(
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.02]}
gravity: [0, 0, -9.81]
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, friction: 0.3}
particles:
  - {material: m, radius: 0.0005, count: 40, placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.02]}}}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: m}
  - {type: cylinder, base: [0.005, 0.005, 0], radius: 0.005, height: 0.02, material: m}
time: {dt_rayleigh: 0.2, end: 0.002}
output: {every_steps: 40, progress: false}
)";
  auto s = from_yaml(yaml);
  const fs::path dir = fs::temp_directory_path() / "grains_test_vtk";
  const auto sum = run_into(s, dir);
  ASSERT_TRUE(fs::exists(dir / "particles.pvd"));
  ASSERT_TRUE(fs::exists(dir / "walls.pvd"));
  ASSERT_TRUE(fs::exists(dir / "summary.json"));
  // Every frame listed in the series exists and reads back.
  std::ifstream pvd(dir / "particles.pvd");
  std::stringstream ss;
  ss << pvd.rdbuf();
  const std::string text = ss.str();
  std::size_t frames = 0, pos = 0;
  while ((pos = text.find("file=\"", pos)) != std::string::npos) {
    pos += 6;
    const std::string f = text.substr(pos, text.find('"', pos) - pos);
    ASSERT_TRUE(fs::exists(dir / f)) << f;
    ++frames;
  }
  EXPECT_EQ(frames, sum.frames);
  EXPECT_EQ(frames, static_cast<std::size_t>(s.scene.clock.n_steps / 40 + 1 + (s.scene.clock.n_steps % 40 ? 1 : 0)));
  vtkNew<vtkXMLUnstructuredGridReader> r;
  r->SetFileName((dir / "frames/particles_000000.vtu").c_str());
  r->Update();
  auto* grid = r->GetOutput();
  ASSERT_EQ(grid->GetNumberOfPoints(), 40);
  for (const char* name : {"id", "radius", "velocity", "force", "coordination", "material", "angular_velocity"})
    EXPECT_NE(grid->GetPointData()->GetArray(name), nullptr) << name;
  EXPECT_DOUBLE_EQ(grid->GetPointData()->GetArray("radius")->GetTuple1(0), 0.0005);
  vtkNew<vtkXMLPolyDataReader> w;
  w->SetFileName((dir / "frames/walls_000000.vtp").c_str());
  w->Update();
  EXPECT_EQ(w->GetOutput()->GetNumberOfCells(), 1 + 64);  // a plane quad and 64 cylinder facets
  EXPECT_EQ(grid->GetPointData()->GetArray("frozen"), nullptr) << "only scenes with frozen grains have it";
  fs::remove_all(dir);
}

TEST(VtkOutput, FrozenGrainsAreMarked) {
  const std::string yaml = R"(
domain: {min: [0, 0, -0.001], max: [0.01, 0.01, 0.02]}
gravity: [0, 0, -9.81]
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, friction: 0.3}
particles:
  - {name: base, material: m, radius: 0.0005, frozen: true, placement: {type: lattice, region: {min: [0, 0, -0.0005], max: [0.01, 0.01, 0.0005]}}}
  - {name: bed, material: m, radius: 0.0005, count: 30, placement: {type: random_fill, region: {min: [0, 0, 0.001], max: [0.01, 0.01, 0.02]}}}
time: {dt_rayleigh: 0.2, end: 0.002}
output: {every_steps: 1000000, progress: false}
)";
  auto s = from_yaml(yaml);
  const fs::path dir = fs::temp_directory_path() / "grains_test_vtk_frozen";
  (void)run_into(s, dir);
  vtkNew<vtkXMLUnstructuredGridReader> r;
  r->SetFileName((dir / "frames/particles_000000.vtu").c_str());
  r->Update();
  auto* pd = r->GetOutput()->GetPointData();
  auto* frozen = pd->GetArray("frozen");
  ASSERT_NE(frozen, nullptr);
  int held = 0;
  const vtkIdType n = r->GetOutput()->GetNumberOfPoints();
  for (vtkIdType k = 0; k < n; ++k) {
    const bool base = r->GetOutput()->GetPoint(k)[2] == 0.0;  // the lattice's plane; the bed starts above 0.0015
    EXPECT_EQ(frozen->GetTuple1(k), base ? 1.0 : 0.0) << "point " << k;
    held += base;
  }
  EXPECT_EQ(held, n - 30);
  fs::remove_all(dir);
}

// summary.json's memory report (docs/memory.md): every part per particle,
// the fields exact (their arrays hold exactly the grains placed), the parts
// adding up to the counted total, and a peak resident size above it; and the
// set-up times.
TEST(Summary, MemoryPerParticleAndSetUpTimes) {
  const std::string j = run_summary(small_bed(), "grains_test_summary_memory");
  auto number = [&](const std::string& key) {
    EXPECT_NE(j.find("\"" + key + "\": "), std::string::npos) << key << " in " << j;
    return json_number(j, key);
  };
  EXPECT_EQ(number("field:position"), 24.0);
  EXPECT_EQ(number("field:velocity"), 24.0);
  EXPECT_EQ(number("field:id"), 8.0);
  EXPECT_EQ(number("field:wall_history"), 24.0);  // one plane, a 3-double spring per grain
  EXPECT_GT(number("contact_history"), 0.0);
  EXPECT_GT(number("neighbor_partners"), 0.0);
  // The parts add up to the counted total.
  const auto parts = j.find("\"bytes_per_particle\": {");
  ASSERT_NE(parts, std::string::npos);
  double sum = 0;
  for (auto at = j.find(": ", parts + 24); at < j.find('}', parts); at = j.find(": ", at + 1))
    sum += std::stod(j.substr(at + 2));
  EXPECT_NEAR(sum, number("counted_bytes_per_particle"), 1e-6 * sum);
  EXPECT_GT(number("peak_resident_bytes"), 200 * number("counted_bytes_per_particle"));
  const std::string setup_key = "\"setup_seconds\": {\"case\": ";
  const auto setup = j.find(setup_key);
  ASSERT_NE(setup, std::string::npos);
  EXPECT_GE(std::stod(j.substr(setup + setup_key.size())), 0.0);
  EXPECT_GT(number("scene"), 0.0);
  // The copy of the sphere pair kernel that ran, by name.
  const std::string simd = std::string("\"sphere_pair_simd\": \"") +
                           (sim::sphere_lanes_enabled() ? sim::sphere_lanes_instruction_set() : "scalar") + "\"";
  EXPECT_NE(j.find(simd), std::string::npos) << j;
}

// Ordered force sums (parallel.deterministic) hold each list entry's two
// sides, force and torques, 96 bytes, and with the sphere lanes (the compact
// layout) the entry's record, 4 bytes, beside one zero record: the memory
// report counts them (with the gather's order), and a run in list order
// holds none.
TEST(Summary, MemoryCountsOrderedSums) {
  auto run_json = [](bool deterministic) {
    return run_summary(small_bed(std::string("parallel: {deterministic: ") + (deterministic ? "true" : "false") + "}\n"),
                       "grains_test_summary_ordered_sums");
  };
  const std::string ordered = run_json(true), plain = run_json(false);
  const double partners = json_number(ordered, "neighbor_partners");  // 4 bytes per list entry
  ASSERT_GT(partners, 0.0) << ordered;
  // (Bytes per grain: the zero record's 96 shared by all.)
  const double entries = partners / 4, lanes = sim::sphere_lanes_enabled() ? 1 : 0;
  EXPECT_DOUBLE_EQ(json_number(ordered, "ordered_sums_entry_forces"),
                   entries * (96 + 4 * lanes) + lanes * 96 / json_number(ordered, "particles_end"))
      << ordered;
  EXPECT_GT(json_number(ordered, "neighbor_ordered_sums"), 0.0) << ordered;
  EXPECT_EQ(json_number(plain, "ordered_sums_entry_forces"), -1.0) << plain;  // absent: none held
  EXPECT_EQ(json_number(plain, "neighbor_ordered_sums"), -1.0) << plain;
  EXPECT_GT(json_number(ordered, "counted_bytes_per_particle"), json_number(plain, "counted_bytes_per_particle") + 0.9 * partners / 4 * 96);
}

TEST(VtkOutput, UnwritableFolderIsAClearError) {
  const std::string yaml = R"(
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
materials:
  - {name: m, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3}
particles:
  - {material: m, radius: 0.0005, count: 5, placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}}
time: {dt_rayleigh: 0.2, end: 0.0001}
)";
  auto s = from_yaml(yaml);
  io::RunOptions opt;
  opt.out_dir = "/proc/grains_cannot_write_here";
  opt.quiet = true;
  try {
    io::run(s, opt);
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/grains_cannot_write_here"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace grains::test
