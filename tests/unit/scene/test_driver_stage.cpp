// A driver stage (an integrator that evaluates the force phase itself, as
// the ARKODE one does) replaces the other non-output phases of a step, and
// the pipeline books each stage's own time only.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "sim/scene/stage.hpp"

namespace grains::sim {
namespace {

class Counting final : public Stage {
 public:
  Counting(Phase ph, int& count, double sleep_s = 0) : ph_(ph), count_(count), sleep_(sleep_s) {}
  std::string name() const override { return "counting"; }
  Phase phase() const override { return ph_; }
  void run(Scene&) override {
    ++count_;
    if (sleep_ > 0) std::this_thread::sleep_for(std::chrono::duration<double>(sleep_));
  }

 private:
  Phase ph_;
  int& count_;
  double sleep_;
};

class Driver final : public Stage {
 public:
  explicit Driver(int evaluations) : n_(evaluations) {}
  std::string name() const override { return "driver"; }
  Phase phase() const override { return Phase::Drift; }
  void run(Scene&) override { FAIL() << "a driver is driven"; }
  bool is_driver() const override { return true; }
  void drive(Scene& s, Pipeline& p) override {
    seen_dt = s.clock.dt;
    for (int k = 0; k < n_; ++k) p.run_phase(s, Phase::Force);
  }
  double seen_dt = -1;

 private:
  int n_;
};

TEST(DriverStage, RunsTheForcePhaseItselfAndReplacesTheOtherPhases) {
  int drift = 0, neighbor = 0, force = 0, kick = 0, output = 0;
  Pipeline p;
  p.add(std::make_unique<Counting>(Phase::Output, output));
  p.add(std::make_unique<Counting>(Phase::Force, force, 0.002));
  p.add(std::make_unique<Counting>(Phase::Kick, kick));
  p.add(std::make_unique<Counting>(Phase::Neighbor, neighbor));
  auto d = std::make_unique<Driver>(3);
  Driver* driver = d.get();
  p.add(std::move(d));
  p.add(std::make_unique<Counting>(Phase::Drift, drift));
  Scene s;
  s.clock.dt = 0.5;
  p.initialize(s);  // neighbour and force phases once, at dt = 0
  EXPECT_EQ(neighbor, 1);
  EXPECT_EQ(force, 1);
  EXPECT_EQ(s.clock.dt, 0.5);
  p.step(s);
  p.step(s);
  EXPECT_EQ(force, 1 + 2 * 3);
  EXPECT_EQ(neighbor, 1);
  EXPECT_EQ(drift + kick, 0);
  EXPECT_EQ(output, 2);
  EXPECT_EQ(driver->seen_dt, 0.5);
  EXPECT_DOUBLE_EQ(s.clock.time, 1.0);
  // Exclusive times: the 7 force evaluations (>= 14 ms of sleep) belong to
  // the force stage; the driver itself does next to nothing.
  const auto names = p.stage_names();
  const auto& sec = p.stage_seconds();
  double force_s = -1, driver_s = -1;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (names[k] == "force: counting") force_s = sec[k];
    if (names[k] == "drift: driver") driver_s = sec[k];
  }
  EXPECT_GE(force_s, 0.014);
  EXPECT_GE(driver_s, 0.0);
  EXPECT_LT(driver_s, 0.5 * force_s);
}

TEST(DriverStage, OnePerPipeline) {
  Pipeline p;
  p.add(std::make_unique<Driver>(1));
  EXPECT_THROW(p.add(std::make_unique<Driver>(1)), std::logic_error);
}

}  // namespace
}  // namespace grains::sim
