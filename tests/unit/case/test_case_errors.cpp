// One test per class of malformed case input: the message says what is
// wrong, where (file:line:column), and what would be valid.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"
#include "tests/support/case_errors.hpp"

namespace grains::io {
namespace {

using test::errors_of;

const std::string kGood = R"(domain:
  min: [0, 0, 0]
  max: [0.01, 0.01, 0.01]
materials:
  - name: glass
    density: 2500
    youngs_modulus: 1.0e7
    poisson_ratio: 0.3
    friction: 0.5
particles:
  - material: glass
    radius: 0.0005
    count: 10
    placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}
time:
  dt: 1.0e-6
  end: 1.0e-4
)";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

TEST(CaseErrors, GoodCaseIsAccepted) { EXPECT_NO_THROW((void)make_simulation(parse_case(kGood, "case.yaml"))); }

TEST(CaseErrors, UnknownKeySuggestsTheClosest) {
  const auto m = errors_of(replace(kGood, "    friction: 0.5", "    frction: 0.5"));
  EXPECT_NE(m.find("case.yaml:9:5: materials[0]: unknown key 'frction'; did you mean 'friction'?"), std::string::npos) << m;
  EXPECT_NE(m.find("valid keys: name, density"), std::string::npos) << m;
}

TEST(CaseErrors, WrongType) {
  const auto m = errors_of(replace(kGood, "density: 2500", "density: heavy"));
  EXPECT_NE(m.find("case.yaml:6:14: materials[0]: density must be a finite number, got 'heavy'"), std::string::npos) << m;
  const auto v = errors_of(replace(kGood, "min: [0, 0, 0]\n  max", "min: [0, 0]\n  max"));
  EXPECT_NE(v.find("case.yaml:2:8: domain: min must be a vector of 3 numbers [x, y, z], got a list with 2 entries"),
            std::string::npos) << v;
}

TEST(CaseErrors, MissingRequiredKey) {
  const auto m = errors_of(replace(kGood, "    youngs_modulus: 1.0e7\n", ""));
  EXPECT_NE(m.find("case.yaml:5:5: materials[0]: missing required key 'youngs_modulus' (Young's modulus E, in Pa)"),
            std::string::npos) << m;
  const auto t = errors_of(replace(kGood, "  dt: 1.0e-6\n", ""));
  EXPECT_NE(t.find("time: missing the time step: give dt"), std::string::npos) << t;
}

TEST(CaseErrors, OutOfRangeValues) {
  const auto r = errors_of(replace(kGood, "radius: 0.0005", "radius: -0.0005"));
  EXPECT_NE(r.find("case.yaml:12:13: particles[0]: radius = -0.0005 m is out of range; valid: > 0"), std::string::npos) << r;
  const auto nu = errors_of(replace(kGood, "poisson_ratio: 0.3", "poisson_ratio: 0.5"));
  EXPECT_NE(nu.find("case.yaml:8:20: materials[0]: poisson_ratio = 0.5 is out of range; valid: (-1, 0.5)"),
            std::string::npos) << nu;
  const auto e = errors_of(replace(kGood, "    friction: 0.5", "    restitution: 1.2"));
  EXPECT_NE(e.find("restitution = 1.2 is out of range; valid: (0, 1]"), std::string::npos) << e;
}

TEST(CaseErrors, AllErrorsAreReportedAtOnce) {
  auto bad = replace(kGood, "density: 2500", "density: -1");
  bad = replace(bad, "    friction: 0.5", "    frction: 0.5");
  const auto m = errors_of(bad);
  EXPECT_NE(m.find("density = -1"), std::string::npos) << m;
  EXPECT_NE(m.find("frction"), std::string::npos) << m;
}

TEST(CaseErrors, UnknownMaterialAndChoice) {
  const auto m = errors_of(replace(kGood, "  - material: glass", "  - material: glas"));
  EXPECT_NE(m.find("case.yaml:11:15: particles[0]: unknown material 'glas'; did you mean 'glass'? defined materials: glass"),
            std::string::npos) << m;
  const auto p = errors_of(replace(kGood, "type: random_fill", "type: randomfill"));
  EXPECT_NE(p.find("placement type 'randomfill' is not valid; did you mean 'random_fill'? valid: random_fill, lattice, file"),
            std::string::npos) << p;
}

TEST(CaseErrors, NonScalarKeysAreErrorsNotCrashes) {
  // Found by tests/fuzz/fuzz_case: a key that is a list, and a tagged key in
  // a flow map, used to escape as a yaml-cpp conversion exception.
  const auto m = errors_of(replace(kGood, "    friction: 0.5", "    ? [a, b]\n    : 0.5"));
  EXPECT_NE(m.find("case.yaml:9:7: materials[0]: keys must be plain names, got a list"), std::string::npos) << m;
  const auto t = errors_of(replace(kGood, "{type: random_fill, region:", "{type: random_fill,!region:"));
  EXPECT_NE(t.find("keys must be plain names"), std::string::npos) << t;
  // Two materials without names: missing keys reported, no crash on the duplicate check.
  const auto d = errors_of(replace(replace(kGood, "  - name: glass\n", "  - density: 1\n"),
                                   "materials:\n", "materials:\n  - {density: 2}\n"));
  EXPECT_NE(d.find("missing required key 'name'"), std::string::npos) << d;
}

TEST(CaseErrors, YamlSyntaxError) {
  const auto m = errors_of(replace(kGood, "  max: [0.01, 0.01, 0.01]", "  max: [0.01, 0.01, 0.01"));
  EXPECT_NE(m.find("case.yaml:"), std::string::npos);
  EXPECT_NE(m.find("YAML syntax error"), std::string::npos) << m;
  EXPECT_NE(errors_of("").find("case.yaml: the case file is empty"), std::string::npos);
}

TEST(CaseErrors, OverlappingInitialParticles) {
  auto dir = std::filesystem::temp_directory_path() / "grains_test_overlap";
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir / "pos.txt");
    f << "# x y z\n0.002 0.002 0.002\n0.0025 0.002 0.002\n";
  }
  auto yaml = replace(kGood, "count: 10\n    placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}",
                      "placement: {type: file, path: " + (dir / "pos.txt").string() + "}");
  const auto m = errors_of(yaml);
  EXPECT_NE(m.find((dir / "pos.txt").string() + ":3: initial particles overlap: particle 1 of set 'set0' and particle 0 of set 'set0' overlap by 0.0005 m (100% of the smaller radius; at most 1% is accepted, neighbor.overlap_tolerance)"),
            std::string::npos) << m;
}

// A wide size distribution is checked by size class (a grid per factor 2 of
// radius): a small grain overlapping a large one is found whichever comes
// first in the file, far from the small grains' cells.
TEST(CaseErrors, OverlappingInitialParticlesOfWideSizes) {
  auto dir = std::filesystem::temp_directory_path() / "grains_test_overlap_wide";
  std::filesystem::create_directories(dir);
  for (const bool small_first : {false, true}) {
    {
      std::ofstream f(dir / "pos.txt");
      f << "# x y z r\n0.001 0.001 0.001 0.0002\n";
      if (small_first)
        f << "0.0071 0.005 0.005 0.0002\n0.005 0.005 0.005 0.002\n";
      else
        f << "0.005 0.005 0.005 0.002\n0.0071 0.005 0.005 0.0002\n";
    }
    auto yaml = replace(kGood, "count: 10\n    placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}",
                        "placement: {type: file, path: " + (dir / "pos.txt").string() + "}");
    const auto m = errors_of(yaml);
    EXPECT_NE(m.find((dir / "pos.txt").string() + ":4: initial particles overlap: particle 2 of set 'set0' and particle 1 of set 'set0' overlap by 0.0001 m (50% of the smaller radius"),
              std::string::npos) << m;
  }
  {  // apart by a hair: accepted
    std::ofstream f(dir / "pos.txt");
    f << "# x y z r\n0.001 0.001 0.001 0.0002\n0.005 0.005 0.005 0.002\n0.00721 0.005 0.005 0.0002\n";
  }
  auto yaml = replace(kGood, "count: 10\n    placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}}",
                      "placement: {type: file, path: " + (dir / "pos.txt").string() + "}");
  EXPECT_NO_THROW((void)io::make_simulation(io::parse_case(yaml, "case.yaml")));
}

TEST(CaseErrors, OverfullFillRegion) {
  const auto m = errors_of(replace(kGood, "count: 10", "count: 5000"));
  EXPECT_NE(m.find("case.yaml:11:5: particle set 'set0': placed only"), std::string::npos) << m;
  EXPECT_NE(m.find("Enlarge placement.region or lower count"), std::string::npos) << m;
}

TEST(CaseErrors, TimeStepAgainstRayleighTime) {
  const auto m = errors_of(replace(kGood, "dt: 1.0e-6", "dt: 1.0e-3"));
  EXPECT_NE(m.find("case.yaml:16:7: time step dt = 0.001 s is"), std::string::npos) << m;
  EXPECT_NE(m.find("Rayleigh times"), std::string::npos) << m;
  // Between 0.3 and 1 Rayleigh times: accepted with a warning.
  auto c = parse_case(replace(kGood, "dt: 1.0e-6", "dt_rayleigh: 0.5"), "case.yaml");
  auto s = make_simulation(std::move(c));
  ASSERT_EQ(s.c.scene.warnings.size(), 0u);  // dt_rayleigh is explicit: no warning
  auto c2 = parse_case(replace(kGood, "dt: 1.0e-6", "dt: 1.5e-5"), "case.yaml");
  auto s2 = make_simulation(std::move(c2));
  ASSERT_EQ(s2.c.scene.warnings.size(), 1u);
  EXPECT_NE(s2.c.scene.warnings[0].find("case.yaml:16:7: warning: time step"), std::string::npos) << s2.c.scene.warnings[0];
}

TEST(CaseErrors, SetOverridesAreValidatedAndLocated) {
  auto c = parse_case(kGood, "case.yaml", {"materials.0.friction=0.1", "time.end=2e-4"});
  EXPECT_DOUBLE_EQ(c.scene.materials[0].friction, 0.1);
  EXPECT_DOUBLE_EQ(c.scene.end_time, 2e-4);
  const auto m = errors_of(kGood, {"materials.0.poisson_ratio=0.7"});
  EXPECT_NE(m.find("--set materials.0.poisson_ratio=0.7: materials[0]: poisson_ratio = 0.7 is out of range"),
            std::string::npos) << m;
  const auto i = errors_of(kGood, {"materials.3.friction=0.1"});
  EXPECT_NE(i.find("'3' is not an index of the list (it has 1 entries"), std::string::npos) << i;
  // A section the case does not have is created by the override.
  auto g = parse_case(kGood, "case.yaml", {"contact.rolling=none"});
  EXPECT_EQ(g.scene.rolling, sim::SlotChoice::None);
  const auto f = errors_of(kGood, {"time.end"});
  EXPECT_NE(f.find("expected key.path=value"), std::string::npos) << f;
}

}  // namespace
}  // namespace grains::io
