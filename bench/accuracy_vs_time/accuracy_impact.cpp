// Two-body normal impact for the accuracy-vs-time report
// (bench/accuracy_vs_time/run.py): runs one impact with velocity Verlet or
// ARKODE and prints one JSON object: the measured restitution, contact time
// and maximum overlap against the Hertz values, the energy error, the
// median wall time over repetitions and the integrator's figures. A set-up
// refusal (e.g. dt above the Rayleigh time) or a non-finite result is
// reported as {"ok": false, "error": ...}: the report shows the failure.
//
//   accuracy_impact --integrator verlet --dt-rayleigh 0.2 [--e 1] [--wall 0] [--v 0.5] [--reps 5]
//   accuracy_impact --integrator arkode --tol 1e-6 [--order 4] [--dt-rayleigh 0.5] ...
//   (--dt-seconds X instead of --dt-rayleigh: an absolute time step)
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/physics/arkode/arkode_impact.hpp"

namespace {

std::string quoted(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (c == '\n') {
      o += "\\n";
      continue;
    }
    o += c;
  }
  return o + "\"";
}

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> a{{"--integrator", "verlet"}, {"--dt-rayleigh", "0.2"}, {"--tol", "1e-6"},
                                       {"--order", "4"},           {"--e", "1"},             {"--wall", "0"},
                                       {"--v", "0.5"},             {"--reps", "5"},
                                       {"--dt-seconds", ""}};
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!a.count(argv[k])) {
      std::cerr << "unknown option " << argv[k] << "\n";
      return 2;
    }
    a[argv[k]] = argv[k + 1];
  }
  grains::test::ImpactSpec c;
  c.e = std::stod(a["--e"]);
  c.wall = a["--wall"] == "1";
  c.v = std::stod(a["--v"]);
  std::ostringstream keys;
  if (a["--dt-seconds"].empty())
    keys << "dt_rayleigh: " << a["--dt-rayleigh"];
  else
    keys << "dt: " << a["--dt-seconds"];
  if (a["--integrator"] == "arkode")
    keys << ", integrator: arkode, rtol: " << a["--tol"] << ", atol: " << a["--tol"] << ", order: " << a["--order"];
  c.time_keys = keys.str();
  const int reps = std::max(1, std::stoi(a["--reps"]));
  std::cout.precision(10);
  try {
    std::vector<double> wall;
    grains::test::ImpactRun r;
    for (int k = 0; k < reps; ++k) {
      r = grains::test::run_impact(c);
      wall.push_back(r.wall_seconds);
    }
    std::sort(wall.begin(), wall.end());
    const bool finite = std::isfinite(r.restitution) && std::isfinite(r.contact_time) && std::isfinite(r.max_overlap);
    std::cout << "{\"ok\": " << (finite ? "true" : "false");
    if (!finite) std::cout << ", \"error\": \"non-finite result (the integration blew up)\"";
    std::cout << ", \"restitution\": " << r.restitution << ", \"contact_time\": " << r.contact_time
              << ", \"max_overlap\": " << r.max_overlap << ", \"tc_hertz\": " << r.tc_hertz
              << ", \"dmax_hertz\": " << r.dmax_hertz << ", \"rayleigh_time\": " << r.rayleigh_time
              << ", \"energy_error\": " << r.energy_drift << ", \"clock_steps\": " << r.clock_steps
              << ", \"wall_median_s\": " << wall[wall.size() / 2] << ", \"reps\": " << reps << ", \"stats\": {"
              << r.stats << "}}\n";
  } catch (const std::exception& e) {
    std::cout << "{\"ok\": false, \"error\": " << quoted(e.what()) << "}\n";
  }
  return 0;
}
