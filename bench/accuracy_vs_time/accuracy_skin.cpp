// Neighbour skin and rebuild frequency against time, with the result
// checked (bench/accuracy_vs_time/run.py). Runs one case once per skin
// (neighbor.skin as a fraction of the largest diameter) and prints one JSON
// line per skin: the median wall time of the time loop over repetitions,
// the neighbour builds, and how far the final state is from the first
// skin's: the largest position difference (in radii) and whether positions
// and velocities are bitwise identical. With parallel.deterministic the
// force sums do not depend on the list's order or size, so the result
// must not change at all; without it the summation order changes with the
// rebuilds and round-off grows through the collisions.
//
//   accuracy_skin CASE.yaml [--set key=value ...] [--reps N] skin...
#include <algorithm>
#include <chrono>
#include <cstring>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "io/case/case.hpp"
#include "io/run/simulation.hpp"

namespace {

struct State {
  std::map<std::int64_t, std::pair<grains::sim::Vec3, grains::sim::Vec3>> xv;
  double r = 0;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: accuracy_skin CASE.yaml [--set key=value ...] [--reps N] skin...\n";
    return 2;
  }
  const std::string path = argv[1];
  std::vector<std::string> sets;
  std::vector<double> skins;
  int reps = 3;
  for (int k = 2; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--set" && k + 1 < argc) {
      sets.push_back(argv[++k]);
    } else if (a == "--reps" && k + 1 < argc) {
      reps = std::max(1, std::stoi(argv[++k]));
    } else {
      skins.push_back(std::stod(a));
    }
  }
  std::cout.precision(10);
  State ref;
  for (std::size_t s = 0; s < skins.size(); ++s) {
    std::vector<double> wall;
    long builds = 0;
    State st;
    for (int rep = 0; rep < reps; ++rep) {
      auto o = sets;
      o.push_back("neighbor.skin=" + std::to_string(skins[s]));
      auto sim = grains::io::make_simulation(grains::io::load_case(path, o));
      auto& sc = sim.scene;
      const auto t0 = std::chrono::steady_clock::now();
      sim.pipeline.initialize(sc);
      while (sc.clock.step < sc.clock.n_steps) sim.pipeline.step(sc);
      wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      builds = sc.neighbors.stats().builds;
      st.xv.clear();
      const auto& p = sc.particles;
      for (std::size_t i = 0; i < p.n_owned(); ++i) {
        st.xv[p.id[i]] = {p.x[i], p.v[i]};
        st.r = i == 0 ? p.radius[i] : std::min(st.r, p.radius[i]);
      }
    }
    if (s == 0) ref = st;
    double dx = 0;
    bool identical = st.xv.size() == ref.xv.size();
    for (const auto& [id, xv] : st.xv) {
      const auto it = ref.xv.find(id);
      if (it == ref.xv.end()) {
        identical = false;
        continue;
      }
      dx = std::max(dx, (xv.first - it->second.first).norm());
      identical = identical && std::memcmp(xv.first.data(), it->second.first.data(), 3 * sizeof(double)) == 0 &&
                  std::memcmp(xv.second.data(), it->second.second.data(), 3 * sizeof(double)) == 0;
    }
    std::sort(wall.begin(), wall.end());
    std::cout << "{\"skin\": " << skins[s] << ", \"wall_median_s\": " << wall[wall.size() / 2] << ", \"reps\": " << reps
              << ", \"builds\": " << builds << ", \"max_dx_over_r\": " << dx / ref.r
              << ", \"identical\": " << (identical ? "true" : "false") << ", \"particles\": " << st.xv.size() << "}\n";
  }
  return 0;
}
