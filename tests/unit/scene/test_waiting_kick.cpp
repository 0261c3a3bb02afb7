// The kick that waits for the next drift (Pipeline::step with may_wait):
//  - the pipeline leaves a kick-phase stage waiting only when it can wait,
//    is the kick phase's one stage, there is no driver, and no output stage
//    reads the state at the step the clock then shows; settle() does it;
//  - in a real scene of frictional spheres falling into a box (rotation,
//    gravity, walls, contacts), the waiting kick changes no bit: the state
//    after settle() is the state of plain steps, at every check and at the end.
#include <gtest/gtest.h>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {
namespace {

struct Log {
  int run = 0, wait = 0, settle = 0;
};

class Kick final : public Stage {
 public:
  Kick(Log& log, bool can) : log_(log), can_(can) {}
  std::string name() const override { return "kick"; }
  Phase phase() const override { return Phase::Kick; }
  void run(Scene&) override { ++log_.run; }
  bool can_wait() const override { return can_; }
  void wait(Scene&) override {
    ++log_.wait;
    waiting_ = true;
  }
  void settle(Scene&) override {
    if (waiting_) ++log_.settle;
    waiting_ = false;
  }

 private:
  Log& log_;
  bool can_;
  bool waiting_ = false;
};

// Reads the state every third step.
class Reader final : public Stage {
 public:
  std::string name() const override { return "reader"; }
  Phase phase() const override { return Phase::Output; }
  void run(Scene&) override {}
  bool reads_state(const Scene& s) const override { return s.clock.step % 3 == 0; }
};

class Plain final : public Stage {  // says nothing: it may read the state
 public:
  explicit Plain(Phase ph) : ph_(ph) {}
  std::string name() const override { return "plain"; }
  Phase phase() const override { return ph_; }
  void run(Scene&) override {}

 private:
  Phase ph_;
};

TEST(WaitingKick, WaitsOnlyAtStepsNoOutputReads) {
  Log log;
  Pipeline p;
  p.add(std::make_unique<Reader>());
  p.add(std::make_unique<Kick>(log, true));
  Scene s;
  s.clock.dt = 0.1;
  for (int k = 0; k < 6; ++k) p.step(s, true);  // steps 1..6: read at 3 and 6
  EXPECT_EQ(log.run, 2);
  EXPECT_EQ(log.wait, 4);
  EXPECT_EQ(log.settle, 0);  // nothing settled before step 3: no second wait was pending
  p.step(s, true);           // step 7 waits
  p.settle(s);
  p.settle(s);  // once only
  EXPECT_EQ(log.settle, 1);
  EXPECT_EQ(s.clock.step, 7);
  p.step(s);  // without may_wait it runs
  EXPECT_EQ(log.run, 3);
  EXPECT_EQ(log.wait, 5);
  p.step(s, true);  // step 9 is read: it runs
  EXPECT_EQ(log.run, 4);
  p.step(s, true);  // step 10 waits
  EXPECT_EQ(log.wait, 6);
  p.finish(s);  // finish settles first
  EXPECT_EQ(log.settle, 2);
}

// Four steps with may_wait of a pipeline of the kick and `other` (if any).
Log four_steps(bool can_wait, std::unique_ptr<Stage> other) {
  Log log;
  Pipeline p;
  p.add(std::make_unique<Kick>(log, can_wait));
  if (other) p.add(std::move(other));
  Scene s;
  for (int k = 0; k < 4; ++k) p.step(s, true);
  return log;
}

TEST(WaitingKick, NeverWaitsWhenItCannotOrIsNotAloneOrAnOutputSaysNothing) {
  const Log alone = four_steps(true, nullptr);
  EXPECT_EQ(alone.wait, 4);  // the case the others differ from
  const Log cannot = four_steps(false, nullptr);
  const Log second = four_steps(true, std::make_unique<Plain>(Phase::Kick));  // a servo's stage beside it
  const Log output = four_steps(true, std::make_unique<Plain>(Phase::Output));  // reads, for all anyone knows
  for (const Log& log : {cannot, second, output}) {
    EXPECT_EQ(log.run, 4);
    EXPECT_EQ(log.wait, 0);
  }
}

// Frictional spheres dropped into a box under strong gravity: they hit the
// floor and each other within the steps run.
io::Simulation falling_spheres() {
  return io::make_simulation(io::parse_case(R"(domain: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}
materials:
  - {name: a, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}
particles:
  - {material: a, radius: 0.0005, count: 150, placement: {type: random_fill, region: {min: [0, 0, 0], max: [0.01, 0.01, 0.01]}, seed: 7}}
gravity: [300, 0, -2000]
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: a}
  - {type: plane, point: [0.01, 0, 0], normal: [-1, 0, 0], material: a}
time: {dt: 2.0e-6, end: 1.0}
)",
                                            "falling.yaml"));
}

TEST(WaitingKick, FallingSpheresGetTheSameBits) {
  auto a = falling_spheres();
  auto b = falling_spheres();
  ASSERT_EQ(a.pipeline.stage_names().back(), "kick: verlet.kick+rotation");
  a.pipeline.initialize(a.scene);
  b.pipeline.initialize(b.scene);
  const auto& pa = a.scene.particles;
  const auto& pb = b.scene.particles;
  auto same = [&] {
    if (pa.n_owned() != pb.n_owned()) return false;
    for (std::size_t i = 0; i < pa.n_owned(); ++i)
      if (pa.id[i] != pb.id[i] || pa.x[i] != pb.x[i] || pa.v[i] != pb.v[i] || pa.omega[i] != pb.omega[i]) return false;
    return true;
  };
  int waited = 0;
  for (int k = 1; k <= 4000; ++k) {
    a.pipeline.step(a.scene);
    b.pipeline.step(b.scene, true);
    if (k % 500 == 0) {
      waited += same() ? 0 : 1;  // b's last kick waits: its velocities are half a kick behind
      b.pipeline.settle(b.scene);
      ASSERT_TRUE(same()) << "after settle at step " << k;
    }
  }
  EXPECT_EQ(waited, 8);
  std::size_t spinning = 0, low = 0;
  for (std::size_t i = 0; i < pa.n_owned(); ++i) {
    spinning += pa.omega[i].norm() > 1.0 ? 1 : 0;
    low += pa.x[i].z() < 0.002 ? 1 : 0;
  }
  EXPECT_GT(spinning, 20u);  // contacts with friction happened
  EXPECT_GT(low, 20u);       // on the floor
}

}  // namespace
}  // namespace grains::sim
