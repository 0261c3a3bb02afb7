#pragma once
// A bracketing root finder for the one-dimensional maximisations of the wall
// contacts (depth along an annulus rim, along a mesh edge).
#include <cmath>

namespace grains::contact {

// Root of a continuous g on [a, b] with g(a) <= 0 <= g(b) (Illinois).
template <class G>
inline double illinois(G&& g, double a, double b, double ga, double gb) {
  int side = 0;
  for (int it = 0; it < 100 && b - a > 1e-14 * (1.0 + std::abs(a)); ++it) {
    const double m = (ga != gb) ? a - ga * (b - a) / (gb - ga) : 0.5 * (a + b);
    const double t = (m > a && m < b) ? m : 0.5 * (a + b);
    const double gt = g(t);
    if (gt == 0.0) return t;
    if (gt < 0.0) {
      a = t, ga = gt;
      if (side == -1) gb *= 0.5;
      side = -1;
    } else {
      b = t, gb = gt;
      if (side == 1) ga *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (a + b);
}

}  // namespace grains::contact
