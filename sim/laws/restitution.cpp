#include "sim/laws/restitution.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

namespace grains::sim {

namespace {

// Right-hand side of u'' = -max(0, u^{3/2} + a u^{1/4} u').
inline double accel(double u, double w, double a) {
  if (u <= 0) return 0.0;
  const double s = std::sqrt(u);
  const double f = u * s + a * std::sqrt(s) * w;
  return f > 0 ? -f : 0.0;
}

}  // namespace

double restitution_for_damping(double a) {
  // The undamped contact lasts s ~ 3.2 in these units; damping shortens it.
  // With h = 5e-5 the result is converged to ~1e-9 (halving h changes it less).
  const double h = 5e-5;
  double u = 0, w = 1;
  for (long k = 0; k < 10'000'000; ++k) {
    const double k1u = w, k1w = accel(u, w, a);
    const double k2u = w + 0.5 * h * k1w, k2w = accel(u + 0.5 * h * k1u, w + 0.5 * h * k1w, a);
    const double k3u = w + 0.5 * h * k2w, k3w = accel(u + 0.5 * h * k2u, w + 0.5 * h * k2w, a);
    const double k4u = w + h * k3w, k4w = accel(u + h * k3u, w + h * k3w, a);
    const double un = u + h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u);
    const double wn = w + h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
    if (un <= 0 && k > 0) {
      // Separation between u and un: interpolate the exit velocity linearly.
      const double t = u / (u - un);
      return -(w + t * (wn - w));
    }
    u = un;
    w = wn;
    // Clamped force zero while receding: the body leaves with constant speed.
    if (w < 0 && accel(u, w, a) == 0.0) return -w;
  }
  return 0.0;
}

double damping_for_restitution(double e) {
  if (!(e > 0.0 && e <= 1.0))
    throw std::invalid_argument("restitution must be in (0, 1], got " + std::to_string(e));
  if (e == 1.0) return 0.0;
  static std::mutex mtx;
  static std::map<double, double> cache;
  {
    std::lock_guard<std::mutex> lock(mtx);
    if (auto it = cache.find(e); it != cache.end()) return it->second;
  }
  // e(a) decreases monotonically from 1 at a = 0. Bracket, then bisect in a.
  double lo = 0.0, hi = 1.0;
  while (restitution_for_damping(hi) > e) {
    lo = hi;
    hi *= 2;
    if (hi > 1e6) throw std::invalid_argument("restitution " + std::to_string(e) + " is too small to calibrate");
  }
  for (int it = 0; it < 60 && hi - lo > 1e-10 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (restitution_for_damping(mid) > e ? lo : hi) = mid;
  }
  const double a = 0.5 * (lo + hi);
  std::lock_guard<std::mutex> lock(mtx);
  cache[e] = a;
  return a;
}

double liggghts_damping(double e) {
  const double l = std::log(e);
  const double beta = l / std::sqrt(l * l + M_PI * M_PI);
  return -std::sqrt(5.0) * beta;
}

}  // namespace grains::sim
