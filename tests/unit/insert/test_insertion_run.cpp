// The insertion effect in runs: the stage exists only when a case asks for
// it, inserted grains overlap nothing at the step they appear (spheres,
// ellipsoids, clumps), the run continues stably, a restart from a checkpoint
// taken before or after an insertion continues bitwise, and mistakes in
// insert[] are reported with their case-file location.
#include <gtest/gtest.h>

#include <algorithm>

#include "contact/ellipsoid/pw85.hpp"
#include "io/case/case.hpp"
#include "io/checkpoint/checkpoint.hpp"
#include "io/run/simulation.hpp"
#include "sim/insert/insertion_stage.hpp"
#include "tests/support/case_errors.hpp"
#include "tests/unit/checkpoint/checkpoint_scene.hpp"

namespace grains::test {
namespace {

// 300 spheres (r = 0.5 mm) dropped into a 1 cm box with walls; `insert` is
// the text of an insert[] entry.
std::string bed_case(const std::string& insert, const std::string& extra = "") {
  return R"(
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.012]}
gravity: [0, 0, -9.81]
materials:
  - {name: grain, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}
particles:
  - name: bed
    material: grain
    radius: 0.0005
    count: 300
    placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.012]}, seed: 3}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain}
  - {type: plane, name: x0, point: [0, 0, 0], normal: [1, 0, 0], material: grain}
  - {type: plane, name: x1, point: [0.01, 0, 0], normal: [-1, 0, 0], material: grain}
  - {type: plane, name: y0, point: [0, 0, 0], normal: [0, 1, 0], material: grain}
  - {type: plane, name: y1, point: [0, 0.01, 0], normal: [0, -1, 0], material: grain}
time: {dt: 4.0e-6, end: 0.008}
output: {vtk: false, progress: false}
insert:
)" + insert + extra;
}

const std::string kFines = R"(  - name: fines
    material: grain
    radius: 0.00025
    count: 120
    at: 0.0012
    region: {min: [0, 0, 0], max: [0.01, 0.01, 0.012]}
    method: fft
    seed: 4
)";

io::RunOptions quiet_into(const fs::path& dir) {
  io::RunOptions o;
  o.out_dir = dir;
  o.quiet = true;
  return o;
}

// Checks, at the step grains were inserted, that no grain with an id from
// `first_new` on overlaps any other grain or a wall (brute force over all
// pairs; ellipsoids by PW85, clump balls as spheres).
class CheckInserted final : public sim::Stage {
 public:
  CheckInserted(std::int64_t step, std::int64_t first_new) : step_(step), first_(first_new) {}
  std::string name() const override { return "test.check_inserted"; }
  sim::Phase phase() const override { return sim::Phase::Output; }
  void run(sim::Scene& s) override {
    if (s.clock.step != step_) return;
    checked = true;
    const auto& p = s.particles;
    const bool ell = p.fields().has(sim::Field::ShapeForm);
    const bool body = p.fields().has(sim::Field::Body);
    auto form = [&](std::size_t i) {
      const double r = p.radius[i];
      return ell && p.shape[i] == sim::kEllipsoid ? p.form[i] : contact::SymMat3{r * r, 0, 0, r * r, 0, r * r};
    };
    for (std::size_t i = 0; i < p.n_owned(); ++i) {
      if (p.id[i] < first_) continue;
      ++inserted;
      const bool ei = ell && p.shape[i] == sim::kEllipsoid;
      for (const auto& w : s.walls.of<sim::PlaneWall>()) {
        const double h = ei ? contact::support(p.form[i], w.normal) : p.radius[i];
        if ((p.x[i] - w.point).dot(w.normal) < h) ++overlaps;
      }
      for (std::size_t j = 0; j < p.n_owned(); ++j) {
        if (i == j || (body && p.body[i] >= 0 && p.body[i] == p.body[j])) continue;
        const sim::Vec3 r = p.x[j] - p.x[i];
        const double bi = ei ? p.semi_axes[i].maxCoeff() : p.radius[i];
        const bool ej = ell && p.shape[j] == sim::kEllipsoid;
        const double bj = ej ? p.semi_axes[j].maxCoeff() : p.radius[j];
        if (r.norm() >= bi + bj) continue;
        if (!ei && !ej) {
          ++overlaps;
          continue;
        }
        if (contact::pw85_contact(r, form(i), form(j)).mu2 < 1) ++overlaps;
      }
    }
  }
  bool checked = false;
  int inserted = 0, overlaps = 0;

 private:
  std::int64_t step_, first_;
};

TEST(InsertionRun, OnlyAScenethatAsksHasTheStage) {
  const std::string plain = bed_case("", "");
  auto without = io::make_simulation(io::parse_case(plain.substr(0, plain.rfind("insert:")), "case.yaml"));
  for (const auto& n : without.pipeline.stage_names()) EXPECT_EQ(n.find("insert"), std::string::npos) << n;
  auto with = io::make_simulation(io::parse_case(bed_case(kFines), "case.yaml"));
  const auto names = with.pipeline.stage_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "output: insert(fines: fft)"), names.end());
}

void run_and_check(const std::string& yaml, const std::string& name, int min_grains, double max_speed) {
  TempDir tmp(name);
  auto simu = io::make_simulation(io::parse_case(yaml, "case.yaml"));
  const auto n0 = static_cast<std::int64_t>(simu.scene.particles.n_owned());
  auto check = std::make_unique<CheckInserted>(300, n0);
  auto* c = check.get();
  simu.pipeline.add(std::move(check));
  const auto r = io::run(simu, quiet_into(tmp.path));
  EXPECT_TRUE(c->checked);
  const sim::InsertionStage* st = nullptr;
  for (const auto& stage : simu.pipeline.stages())
    if (auto* q = dynamic_cast<const sim::InsertionStage*>(stage.get())) st = q;
  ASSERT_NE(st, nullptr);
  EXPECT_EQ(st->totals()[0].events, 1);
  EXPECT_GE(st->totals()[0].placed, min_grains);
  EXPECT_GE(c->inserted, st->totals()[0].placed);  // clumps: one particle per ball
  EXPECT_EQ(c->overlaps, 0);
  EXPECT_EQ(r.lost_particles, 0);
  EXPECT_EQ(static_cast<int>(simu.scene.particles.n_owned()), n0 + c->inserted);
  // Stable: nothing flies off after the insertion.
  double vmax = 0;
  for (std::size_t i = 0; i < simu.scene.particles.n_owned(); ++i)
    vmax = std::max(vmax, simu.scene.particles.v[i].norm());
  EXPECT_LT(vmax, max_speed);
}

TEST(InsertionRun, SpheresOverlapNothingAndTheRunContinues) {
  run_and_check(bed_case(kFines), "spheres", 120, 0.5);
}

TEST(InsertionRun, EllipsoidsOverlapNothingAndTheRunContinues) {
  std::string e = kFines;
  e.replace(e.find("    method: fft"), 15, "    shape: {type: ellipsoid, aspect_ratio: 2}\n    method: fft\n    orientations: 4");
  run_and_check(bed_case(e), "ellipsoids", 100, 0.5);
}

TEST(InsertionRun, ClumpsOverlapNothingAndTheRunContinues) {
  std::string e = kFines;
  e.replace(e.find("    radius: 0.00025"), 19, "    radius: 0.0004");
  e.replace(e.find("    count: 120"), 14, "    count: 40");
  e.replace(e.find("    method: fft"), 15,
            std::string("    shape: {type: clump, mesh: ") + GRAINS_SOURCE_DIR +
                "/tests/data/meshes/cube.off, grid: 6}\n    method: fft\n    orientations: 4");
  run_and_check(bed_case(e), "clumps", 40, 0.5);
}

TEST(InsertionRun, RestartBeforeAtAndAfterAnInsertionIsBitwise) {
  TempDir tmp("insert_restart");
  const std::string yaml = bed_case(kFines, "checkpoint: {every_steps: 50, keep: 100}\n");
  auto full = io::make_simulation(io::parse_case(yaml, "case.yaml"));
  io::run(full, quiet_into(tmp.path / "full"));
  EXPECT_GT(full.scene.particles.n_owned(), 300u);
  // The insertion is at step 300: restarts from before it, from the step
  // itself (the new grains are in the checkpoint, their pairs not yet in the
  // list) and from after it.
  for (std::int64_t from : {250, 300, 500}) {
    auto part = io::make_simulation(io::parse_case(yaml, "case.yaml"));
    auto opt = quiet_into(tmp.path / ("part" + std::to_string(from)));
    opt.restart = tmp.path / "full" / "checkpoints" / io::checkpoint_name(from);
    io::run(part, opt);
    SCOPED_TRACE("restart from step " + std::to_string(from));
    expect_same_state(full.scene, part.scene);
  }
}

std::string with(std::string s, const std::string& from, const std::string& to) {
  const auto p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  return s.replace(p, from.size(), to);
}

TEST(InsertionRun, CaseErrorsSayWhatAndWhere) {
  // insert[0] starts at line 21, column 5 of bed_case.
  const std::string good = bed_case(kFines);
  auto m = errors_of(with(good, "    seed: 4", "    sead: 4"));
  EXPECT_NE(m.find("case.yaml:28:5: insert[0]: unknown key 'sead'; did you mean 'seed'? valid keys: name, material,"),
            std::string::npos) << m;
  m = errors_of(with(good, "method: fft", "method: fast"));
  EXPECT_NE(m.find("case.yaml:27:13: insert[0]: method = 'fast' is not valid; did you mean 'fft'? valid: fft, random"), std::string::npos) << m;
  m = errors_of(with(good, "method: fft", "method: random\n    margin: 0.5"));
  EXPECT_NE(m.find("case.yaml:28:13: insert[0]: 'margin' applies to method: fft only"), std::string::npos) << m;
  m = errors_of(with(good, "    count: 120\n", ""));
  EXPECT_NE(m.find("case.yaml:21:5: insert[0]: missing required key 'count' (grains asked for at each insertion)"),
            std::string::npos) << m;
  m = errors_of(with(good, "count: 120", "count: 0"));
  EXPECT_NE(m.find("case.yaml:24:12: insert[0]: count = 0 is out of range; valid: [1, 1000000000]"), std::string::npos) << m;
  m = errors_of(with(good, "material: grain\n    radius: 0.00025", "material: sand\n    radius: 0.00025"));
  EXPECT_NE(m.find("case.yaml:22:15: insert[0]: unknown material 'sand'"), std::string::npos) << m;
  m = errors_of(with(good, "max: [0.01, 0.01, 0.012]}\n    method", "max: [0.01, 0.01, 0.02]}\n    method"));
  EXPECT_NE(m.find("case.yaml:21:5: insert 'fines': the region reaches outside the domain along z ([0, 0.02] m, the "
                   "domain is [0, 0.012] m); keep it inside the domain"),
            std::string::npos) << m;
  m = errors_of(with(good, "region: {min: [0, 0, 0], max: [0.01, 0.01, 0.012]}\n    method",
                     "region: {min: [0, 0, 0.0116], max: [0.01, 0.01, 0.012]}\n    method"));
  EXPECT_NE(m.find("case.yaml:21:5: insert 'fines': the region is 0.0004 m wide along z, less than the largest "
                   "grain's bounding diameter 0.0005 m; enlarge the region"),
            std::string::npos) << m;
  m = errors_of(with(good, "time: {dt: 4.0e-6, end: 0.008}", "time: {dt: 4.0e-6, end: 0.008, integrator: arkode}"));
  EXPECT_NE(m.find("case.yaml:21:5: insert 'fines': grains cannot be inserted with time.integrator: arkode"),
            std::string::npos) << m;
  m = errors_of(with(good, "method: fft", "method: fft\n    times: 3"));
  EXPECT_NE(m.find("case.yaml:28:12: insert[0]: 'times' caps repeated insertions and applies with every only "
                   "(without every the grains are inserted once)"),
            std::string::npos) << m;
  m = errors_of(with(bed_case(""), "insert:\n", "insert: []\n"));
  EXPECT_NE(m.find("insert: expected a non-empty list of insertions"), std::string::npos) << m;
}

// A scene may start empty and be filled by insertion alone (no particles
// key); `times` caps the number of insertions whatever the rounding of
// `every` to whole steps: 7 insertions of 3 grains, although `every` and
// `until` would allow 10.
TEST(InsertionRun, AnEmptySceneFillsByInsertionAndTimesCapsTheEvents) {
  const std::string yaml = R"(
domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.012]}
gravity: [0, 0, -9.81]
materials:
  - {name: grain, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain}
time: {dt: 4.0e-6, end: 0.006}
output: {vtk: false, progress: false}
insert:
  - {material: grain, radius: 0.0005, count: 3, velocity: [0, 0, -1], method: random,
     region: {min: [0, 0, 0.008], max: [0.01, 0.01, 0.012]}, every: 0.0005, until: 0.0049, times: 7}
)";
  TempDir tmp("empty_start");
  auto simu = io::make_simulation(io::parse_case(yaml, "case.yaml"));
  EXPECT_EQ(simu.scene.particles.n_owned(), 0u);
  const auto r = io::run(simu, quiet_into(tmp.path));
  EXPECT_EQ(simu.scene.particles.n_owned(), 21u);
  EXPECT_EQ(r.lost_particles, 0);
  // The grains fell onto the floor: the walls and lists were built although
  // the scene began with nothing in it.
  for (std::size_t i = 0; i < simu.scene.particles.n_owned(); ++i) {
    EXPECT_GT(simu.scene.particles.x[i].z(), 0.00045);
    EXPECT_LT(simu.scene.particles.x[i].z(), 0.008);
  }
  // Without gravity the inserted grains' own speed is the scene's speed
  // scale: the blow-up check (which knew only initial speeds, the fall and
  // the walls) lets them fly at 1 m/s.
  {
    TempDir tmp2("empty_start_no_gravity");
    std::string g = yaml;
    g.replace(g.find("gravity: [0, 0, -9.81]"), 22, "gravity: [0, 0, 0]");
    auto s2 = io::make_simulation(io::parse_case(g, "case.yaml"));
    EXPECT_NO_THROW(io::run(s2, quiet_into(tmp2.path)));
    EXPECT_EQ(s2.scene.particles.n_owned(), 21u);
  }
  // Without particles and without insert[] a case says what is missing.
  const std::string m = errors_of(yaml.substr(0, yaml.find("insert:")));
  EXPECT_NE(m.find("missing required key 'particles' (particle sets (see particles)); a case needs particles, or "
                   "insert[] to add grains during the run"),
            std::string::npos)
      << m;
}

}  // namespace
}  // namespace grains::test
