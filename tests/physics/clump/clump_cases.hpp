#pragma once
// Clump shapes and scenes shared by the clump dynamics tests.
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <unistd.h>

#include "contact/clump/clump_yaml.hpp"
#include "tests/support/sim_helpers.hpp"

namespace grains::test {

namespace fs = std::filesystem;

/// A folder for clump files and the mesh-decomposition cache of this test
/// process (GRAINS_CACHE_DIR points into it, so tests never touch ~/.cache).
inline const fs::path& clump_test_dir() {
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("grains_clump_dyn_" + std::to_string(::getpid()));
    fs::create_directories(d);
    ::setenv("GRAINS_CACHE_DIR", (d / "cache").c_str(), 1);
    return d;
  }();
  return dir;
}

/// A clump file of a dimer: two balls of radius a whose centres are `bond`
/// apart (bond aspect ratio (bond + 2a) / 2a). Mass properties of the union
/// (contact/clump/ball_union.hpp), integrated to a/128.
inline std::string dimer_file(double a, double bond) {
  std::ostringstream name;
  name << "dimer_" << a << "_" << bond << ".yaml";
  const fs::path path = clump_test_dir() / name.str();
  if (!fs::exists(path)) {
    std::vector<clump::Ball> balls{{Eigen::Vector3d(-bond / 2, 0, 0), a}, {Eigen::Vector3d(bond / 2, 0, 0), a}};
    clump::write_clump_yaml(clump::make_clump_template(balls, 1000.0, a / 128), path.string());
  }
  return path.string();
}

inline std::string cube_mesh() { return std::string(GRAINS_SOURCE_DIR) + "/tests/data/meshes/cube.off"; }

/// Total linear momentum of the free particles and the bodies.
inline sim::Vec3 total_momentum(const sim::Scene& s) {
  sim::Vec3 P = sim::Vec3::Zero();
  for (std::size_t k = 0; k < s.bodies.size(); ++k) P += s.bodies.mass[k] * s.bodies.v[k];
  const auto& p = s.particles;
  for (std::size_t i = 0; i < p.n_owned(); ++i)
    if (!p.fields().has(sim::Field::Body) || p.body[i] < 0) P += p.mass[i] * p.v[i];
  return P;
}

/// Total angular momentum of the bodies about the origin.
inline sim::Vec3 body_angular_momentum(const sim::Scene& s) {
  sim::Vec3 L = sim::Vec3::Zero();
  for (std::size_t k = 0; k < s.bodies.size(); ++k)
    L += s.bodies.x[k].cross(s.bodies.mass[k] * s.bodies.v[k]) + s.bodies.angular_momentum[k];
  return L;
}

inline void run_to_end(io::Simulation& s) {
  s.pipeline.initialize(s.scene);
  while (s.scene.clock.step < s.scene.clock.n_steps) s.pipeline.step(s.scene);
}

}  // namespace grains::test
