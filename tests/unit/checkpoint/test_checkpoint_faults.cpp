// Faults: an unwritable output folder, an output that fails mid-run (the
// state is saved and the run continues exactly from it), and a blow-up that
// never overwrites the last good checkpoint.
#include <fstream>
#include <sstream>

#include <vtkObject.h>

#include "io/checkpoint/checkpoint.hpp"
#include "io/output/progress.hpp"
#include "tests/unit/checkpoint/checkpoint_scene.hpp"

namespace grains::test {
namespace {

TEST(CheckpointFaults, UnwritableOutputFolderFailsBeforeTheRun) {
  TempDir tmp("unwritable");
  std::ofstream(tmp.path / "file") << "not a folder";
  auto s = make(silo_case());
  io::RunOptions o;
  o.out_dir = tmp.path / "file" / "out";
  o.quiet = true;
  try {
    io::run(s, o);
    ADD_FAILURE() << "no error";
  } catch (const io::OutputFailure& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create the output folder '" + o.out_dir.string() + "'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(s.scene.clock.step, 0);
}

// Replaces the frames folder by a file at step `at`, so the next frame fails.
class BreakFramesAt final : public sim::Stage {
 public:
  BreakFramesAt(fs::path dir, std::int64_t at) : dir_(std::move(dir)), at_(at) {}
  std::string name() const override { return "test.break_frames"; }
  sim::Phase phase() const override { return sim::Phase::Output; }
  void run(sim::Scene& s) override {
    if (s.clock.step != at_) return;
    fs::remove_all(dir_ / "frames");
    std::ofstream(dir_ / "frames") << "in the way";
  }

 private:
  fs::path dir_;
  std::int64_t at_;
};

TEST(CheckpointFaults, FailedOutputSavesTheStateAndTheRunContinuesExactly) {
  vtkObject::GlobalWarningDisplayOff();  // the failing VTK writer would print its own trace
  TempDir tmp("outputfail");
  auto full = make(silo_case());
  io::RunOptions of;
  of.out_dir = tmp.path / "full";
  of.quiet = true;
  io::run(full, of);

  auto s = make(silo_case());
  const fs::path out = tmp.path / "broken";
  s.pipeline.add(std::make_unique<BreakFramesAt>(out, 850));  // before the VTK stage
  io::RunOptions o;
  o.out_dir = out;
  o.quiet = true;
  std::string msg;
  try {
    io::run(s, o);
  } catch (const io::OutputFailure& e) {
    msg = e.what();
  }
  ASSERT_FALSE(msg.empty()) << "the broken output was not reported";
  EXPECT_NE(msg.find("could not write"), std::string::npos) << msg;
  EXPECT_NE(msg.find("the run stopped at step 900"), std::string::npos) << msg;
  const fs::path saved = out / "checkpoints" / io::checkpoint_name(900);
  EXPECT_NE(msg.find("its state is saved in " + saved.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("--restart " + saved.string()), std::string::npos) << msg;

  fs::remove(out / "frames");
  auto r = make(silo_case());
  o.restart = saved;
  io::run(r, o);
  expect_same_state(full.scene, r.scene);
  // The frame that failed is written on resume: the series has no gap.
  EXPECT_EQ(read_text(out / "particles.pvd"), read_text(tmp.path / "full" / "particles.pvd"));
}

TEST(CheckpointFaults, FallsBackToTheEmergencyFolder) {
  vtkObject::GlobalWarningDisplayOff();
  TempDir tmp("emergency");
  auto s = make(silo_case());
  const fs::path out = tmp.path / "out";
  // Both frames and checkpoints become impossible at step 850.
  class BreakAll final : public sim::Stage {
   public:
    explicit BreakAll(fs::path d) : d_(std::move(d)) {}
    std::string name() const override { return "test.break_all"; }
    sim::Phase phase() const override { return sim::Phase::Output; }
    void run(sim::Scene& sc) override {
      if (sc.clock.step != 850) return;
      for (const char* sub : {"frames", "checkpoints"}) {
        fs::remove_all(d_ / sub);
        std::ofstream(d_ / sub) << "in the way";
      }
    }
    fs::path d_;
  };
  s.pipeline.add(std::make_unique<BreakAll>(out));
  io::RunOptions o;
  o.out_dir = out;
  o.quiet = true;
  o.emergency_dir = tmp.path / "rescue";
  try {
    io::run(s, o);
    ADD_FAILURE() << "no error";
  } catch (const io::OutputFailure& e) {
    const fs::path saved = tmp.path / "rescue" / io::checkpoint_name(900);
    EXPECT_NE(std::string(e.what()).find("its state is saved in " + saved.string()), std::string::npos) << e.what();
    EXPECT_EQ(io::checkpoint_info(saved).step, 900);
  }
}

TEST(CheckpointFaults, BlowUpIsDiagnosedAndKeepsTheLastGoodCheckpoint) {
  TempDir tmp("blowup");
  // 0.9 Rayleigh times, and two clusters thrown at each other at 20 m/s:
  // each step moves a particle by 1.6 radii, so contacts overlap absurdly.
  const std::string yaml = R"(
domain: {min: [-0.01, -0.01, -0.01], max: [0.03, 0.03, 0.03]}
materials:
  - {name: grain, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.9, friction: 0.5}
particles:
  - {name: a, material: grain, radius: 0.0005, count: 200, velocity: [20, 0, 0],
     placement: {type: random_fill, region: {min: [0.0, 0.0, 0.0], max: [0.004, 0.02, 0.02]}, seed: 3}}
  - {name: b, material: grain, radius: 0.0005, count: 200, velocity: [-20, 0, 0],
     placement: {type: random_fill, region: {min: [0.006, 0.0, 0.0], max: [0.010, 0.02, 0.02]}, seed: 4}}
time: {dt_rayleigh: 0.9, end: 0.01}
output: {vtk: false, progress: false}
checkpoint: {every_steps: 1, keep: 2}
)";
  auto s = make(yaml);
  io::RunOptions o;
  o.out_dir = tmp.path;
  o.quiet = true;
  std::string msg;
  try {
    io::run(s, o);
  } catch (const io::BlowUp& e) {
    msg = e.what();
  }
  ASSERT_FALSE(msg.empty()) << "the blow-up was not detected";
  EXPECT_NE(msg.find("blow-up at step"), std::string::npos) << msg;
  EXPECT_NE(msg.find("particles id "), std::string::npos) << msg;
  EXPECT_NE(msg.find("% of the smaller radius"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Rayleigh times; use time.dt_rayleigh: 0.2"), std::string::npos) << msg;
  const auto kept = io::list_checkpoints(tmp.path / "checkpoints");
  ASSERT_FALSE(kept.empty());
  EXPECT_NE(msg.find("The last good checkpoint is " + kept.back().string()), std::string::npos) << msg;
  // Every kept checkpoint holds a sound state: finite and within the bounds.
  for (const auto& k : kept) {
    auto r = make(yaml);
    io::read_checkpoint(k, r.scene);
    io::BlowUpCheck check(make(yaml).scene, 1.0);
    EXPECT_EQ(check.diagnose(r.scene), "") << k;
    EXPECT_LT(r.scene.clock.step, s.scene.clock.step);
  }
}

}  // namespace
}  // namespace grains::test
