#pragma once
// Scenes and comparisons shared by the checkpoint tests.
#include <csignal>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"

namespace grains::test {

namespace fs = std::filesystem;

/// A frictional, rolling, gravity-driven scene in a cylinder silo whose
/// floor moves: every kind of state a checkpoint carries changes during it.
/// 300 particles, 1500 steps of 8 us.
inline std::string silo_case(const std::string& checkpoint = "{every_steps: 250, keep: 10}") {
  return R"(
domain: {min: [-0.001, -0.001, -0.001], max: [0.013, 0.013, 0.03]}
gravity: [0, 0, -9.81]
materials:
  - {name: grain, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5, rolling_friction: 0.1}
particles:
  - name: spheres
    material: grain
    radius: {distribution: uniform, min: 0.0004, max: 0.0005}
    count: 300
    velocity: [0.1, 0.05, -0.5]
    placement: {type: random_fill, region: {min: [0.002, 0.002, 0.0006], max: [0.010, 0.010, 0.009]}, seed: 7}
walls:
  - {type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain, velocity: [0, 0, 0.02]}
  - {type: cylinder, name: silo, base: [0.006, 0.006, -0.001], radius: 0.006, height: 0.03, material: grain}
time: {dt: 8.0e-6, end: 0.012}
output: {every_steps: 300, progress: false}
checkpoint: )" + checkpoint + "\n";
}

inline io::Simulation make(const std::string& yaml, const std::vector<std::string>& sets = {}) {
  return io::make_simulation(io::parse_case(yaml, "silo.yaml", sets));
}

/// A fresh folder under the system temp folder, removed at the end of the test.
struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name) {
    path = fs::temp_directory_path() / ("grains_ckpt_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

/// Every allocated per-particle field as raw bytes, by name.
inline std::map<std::string, std::string> field_bytes(sim::ParticleStore& p) {
  std::map<std::string, std::string> out;
  p.visit_fields([&](const char* name, const char*, auto& vec, int width) {
    using T = typename std::decay_t<decltype(vec)>::value_type;
    const std::size_t n = p.n_owned() * static_cast<std::size_t>(width);
    out[name] = std::string(reinterpret_cast<const char*>(vec.data()), n * sizeof(T));
  });
  return out;
}

template <class T>
std::string bytes(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

/// Bitwise equality of everything that determines the rest of a run.
inline void expect_same_state(sim::Scene& a, sim::Scene& b) {
  EXPECT_EQ(a.clock.step, b.clock.step);
  EXPECT_EQ(std::memcmp(&a.clock.time, &b.clock.time, sizeof(double)), 0);
  const auto fa = field_bytes(a.particles), fb = field_bytes(b.particles);
  ASSERT_EQ(fa.size(), fb.size());
  for (const auto& [name, data] : fa) {
    ASSERT_TRUE(fb.count(name)) << name;
    EXPECT_TRUE(data == fb.at(name)) << "particle field '" << name << "' differs";
  }
  EXPECT_TRUE(bytes(a.neighbors.row_start) == bytes(b.neighbors.row_start)) << "neighbour rows differ";
  EXPECT_TRUE(bytes(a.neighbors.partner) == bytes(b.neighbors.partner)) << "neighbour partners differ";
  EXPECT_TRUE(bytes(a.neighbors.history) == bytes(b.neighbors.history)) << "contact history differs";
  const auto ba = a.neighbors.build_state(), bb = b.neighbors.build_state();
  EXPECT_EQ(ba.builds, bb.builds);
  EXPECT_TRUE(bytes(ba.x) == bytes(bb.x)) << "build positions differ";
  ASSERT_EQ(a.walls.of<sim::PlaneWall>().size(), b.walls.of<sim::PlaneWall>().size());
  for (std::size_t w = 0; w < a.walls.of<sim::PlaneWall>().size(); ++w) EXPECT_EQ(a.walls.of<sim::PlaneWall>()[w].point, b.walls.of<sim::PlaneWall>()[w].point);
  EXPECT_EQ(a.lost_particles, b.lost_particles);
  EXPECT_EQ(std::memcmp(&ba.growth, &bb.growth, sizeof(double)), 0) << "list growth since the build differs";
  const auto& ga = a.growth;
  const auto& gb = b.growth;
  EXPECT_TRUE(ga.started == gb.started && ga.capped == gb.capped && ga.last_measure == gb.last_measure &&
              bytes(std::vector<double>{ga.overlap, ga.rate, ga.phase_rate, ga.phase_target}) ==
                  bytes(std::vector<double>{gb.overlap, gb.rate, gb.phase_rate, gb.phase_target}))
      << "radius-growth servo differs";
}

/// Raises a signal (as a user's Ctrl-C would) after step `at`.
class RaiseAt final : public sim::Stage {
 public:
  RaiseAt(std::int64_t at, int sig) : at_(at), sig_(sig) {}
  std::string name() const override { return "test.raise"; }
  sim::Phase phase() const override { return sim::Phase::Output; }
  void run(sim::Scene& s) override {
    if (s.clock.step == at_) std::raise(sig_);
  }

 private:
  std::int64_t at_;
  int sig_;
};

inline std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace grains::test
