#pragma once
// Small deterministic ball scenes for the overlap-field tests.
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace grains::correlation::testing {

struct Scene {
  std::vector<double> centres, radii;
};

// Random sequential addition of non-overlapping balls in the periodic box
// [0, L)^3 (minimum-image distances), radii drawn from the given list.
inline Scene rsa_scene(double L, const std::vector<double>& radii_choice, int target, unsigned seed,
                       int max_tries = 200000) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, L);
  Scene s;
  for (int t = 0; t < max_tries && static_cast<int>(s.radii.size()) < target; ++t) {
    const double r = radii_choice[rng() % radii_choice.size()];
    const std::array<double, 3> c = {u(rng), u(rng), u(rng)};
    bool ok = true;
    for (std::size_t i = 0; i < s.radii.size() && ok; ++i) {
      double d2 = 0.0;
      for (int a = 0; a < 3; ++a) {
        double d = c[a] - s.centres[3 * i + a];
        d -= L * std::round(d / L);
        d2 += d * d;
      }
      ok = d2 > (r + s.radii[i]) * (r + s.radii[i]);
    }
    if (!ok) continue;
    s.centres.insert(s.centres.end(), c.begin(), c.end());
    s.radii.push_back(r);
  }
  return s;
}

// Minimum-image distance in a box periodic along the flagged axes.
inline double periodic_distance(const double* a, const double* b, std::array<double, 3> L,
                                std::array<bool, 3> periodic) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    double d = a[k] - b[k];
    if (periodic[k]) d -= L[k] * std::round(d / L[k]);
    d2 += d * d;
  }
  return std::sqrt(d2);
}

}  // namespace grains::correlation::testing
