#pragma once
// The contact part of the stress tensor, gathered by the force stages on the
// steps it is measured (output.stress, io/output/stress_output.hpp); null on
// every other step, so that the force stages do nothing for it then.
//
// Love–Weber: sigma = (1/V) sum_c w_c sym(F_c (x) b_c), compressive > 0, with
// F_c the force on body i of the contact and b_c its branch vector: x_i - x_j
// between two bodies (the centres: exact for rigid bodies in equilibrium,
// whatever their shape), x_i - x_c from a wall's contact point. w_c is the
// fraction of the branch inside the region (of a bin along `axis`): the bin's
// stress is then the method-of-planes stress averaged over the bin, exact in
// a static bed (sigma_zz(z) A = the weight of the grains above z) however
// thin the bins. Along periodic dimensions the parts of a branch outside the
// domain count at their images inside it. A pair with a ghost, which both
// ranks (or both periodic images) compute, counts half each time. Each thread
// adds into its own rows; the output sums them, and the ranks' sums.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "contact/contact_geometry.hpp"

namespace grains::sim {

using contact::Vec3;

struct StressProbe {
  using Sym = std::array<double, 6>;  // xx, yy, zz, xy, xz, yz
  Vec3 lo{0, 0, 0}, hi{0, 0, 0};      // the region
  Vec3 period_lo{0, 0, 0}, period{0, 0, 0};  // the domain along periodic dimensions (period 0: not periodic)
  int axis = 2;
  int bins = 0;  // profile bins along axis over [lo, hi] (0: none)
  /// Lees–Edwards: an image across the gradient is displaced along the flow
  /// by the offset then (flow -1: none).
  int shear_flow = -1, shear_gradient = -1;
  double shear_offset = 0;
  /// The whole domain with no bins (the pressure servo of a sheared cell):
  /// every branch counts once, wholly, in row 0.
  bool whole = false;
  /// Per thread: the region's sum, then one per bin.
  std::vector<std::vector<Sym>> rows;
  /// Another probe armed on the same step (the force stages see only the
  /// first): it gets every contact too.
  StressProbe* next = nullptr;

  /// Zeroed rows for `threads` threads; in place when their shape is kept
  /// (the pressure servo resets every step: no allocation then).
  void reset(int threads) {
    const auto t = static_cast<std::size_t>(threads), b = static_cast<std::size_t>(1 + bins);
    if (rows.size() == t && (t == 0 || rows[0].size() == b)) {
      for (auto& r : rows) std::fill(r.begin(), r.end(), Sym{});
      return;
    }
    rows.assign(t, std::vector<Sym>(b, Sym{}));
  }

  /// The contact of force F on body i at x_i with branch b (from x_i - b to x_i).
  void add(int thread, const Vec3& xi, const Vec3& F, const Vec3& b) {
    const Sym c{F.x() * b.x(), F.y() * b.y(), F.z() * b.z(), 0.5 * (F.x() * b.y() + F.y() * b.x()),
                0.5 * (F.x() * b.z() + F.z() * b.x()), 0.5 * (F.y() * b.z() + F.z() * b.y())};
    if (next) next->add(thread, xi, F, b);
    if (whole) {
      accumulate(rows[static_cast<std::size_t>(thread)][0], c, 1.0);
      return;
    }
    // The images of the branch that reach the domain along periodic
    // dimensions, the gradient's first (its images are displaced along the flow).
    const int g = shear_flow >= 0 ? shear_gradient : 0;
    const int o1 = g == 0 ? 1 : 0, o2 = g == 2 ? 1 : 2;
    auto& r = rows[static_cast<std::size_t>(thread)];
    const Vec3 a = xi - b;
    int kg0, kg1;
    range(a, b, g, kg0, kg1);
    for (int kg = kg0; kg <= kg1; ++kg) {
      Vec3 a1 = a;
      a1[g] -= kg * period[g];
      if (shear_flow >= 0) a1[shear_flow] -= kg * shear_offset;
      int k10, k11;
      range(a1, b, o1, k10, k11);
      for (int k1 = k10; k1 <= k11; ++k1) {
        Vec3 a2 = a1;
        a2[o1] -= k1 * period[o1];
        int k20, k21;
        range(a2, b, o2, k20, k21);
        for (int k2 = k20; k2 <= k21; ++k2) {
          Vec3 a3 = a2;
          a3[o2] -= k2 * period[o2];
          add_segment(r, c, a3, b);
        }
      }
    }
  }

  /// A pair of particles i, j of `p` (positions x): force F on i from j. A
  /// pair with a ghost is computed on both ranks (or, periodic, for both
  /// images): half from each.
  template <class Store>
  void add_pair(int thread, const Store& p, std::size_t i, std::size_t j, const Vec3& F) {
    const bool ghost = i >= p.n_owned() || j >= p.n_owned();
    add(thread, p.x[i], ghost ? Vec3(0.5 * F) : F, p.x[i] - p.x[j]);
  }

 private:
  // The periods along d the segment a + t b reaches (none when not periodic).
  void range(const Vec3& a, const Vec3& b, int d, int& k0, int& k1) const {
    k0 = k1 = 0;
    if (!(period[d] > 0)) return;
    k0 = static_cast<int>(std::floor((std::min(a[d], a[d] + b[d]) - period_lo[d]) / period[d]));
    k1 = static_cast<int>(std::floor((std::max(a[d], a[d] + b[d]) - period_lo[d]) / period[d]));
  }
  static void accumulate(Sym& to, const Sym& c, double w) {
    for (std::size_t k = 0; k < 6; ++k) to[k] += w * c[k];
  }
  // The segment a + t b, t in [0, 1]: its fraction in the region, and in each bin.
  void add_segment(std::vector<Sym>& r, const Sym& c, const Vec3& a, const Vec3& b) const {
    double t0 = 0, t1 = 1;
    for (int d = 0; d < 3; ++d) {
      if (b[d] == 0) {
        if (!(a[d] >= lo[d] && a[d] < hi[d])) return;
        continue;
      }
      double u0 = (lo[d] - a[d]) / b[d], u1 = (hi[d] - a[d]) / b[d];
      if (u0 > u1) std::swap(u0, u1);
      t0 = std::max(t0, u0), t1 = std::min(t1, u1);
    }
    if (!(t1 > t0)) return;
    accumulate(r[0], c, t1 - t0);
    if (bins == 0) return;
    const double w = (hi[axis] - lo[axis]) / bins;
    const auto bin_of = [&](double z) { return std::clamp(static_cast<int>((z - lo[axis]) / w), 0, bins - 1); };
    if (b[axis] == 0) {
      accumulate(r[static_cast<std::size_t>(1 + bin_of(a[axis]))], c, t1 - t0);
      return;
    }
    const double z0 = a[axis] + t0 * b[axis], z1 = a[axis] + t1 * b[axis];
    const int first = bin_of(std::min(z0, z1)), last = bin_of(std::max(z0, z1));
    for (int k = first; k <= last; ++k) {
      double u0 = (lo[axis] + k * w - a[axis]) / b[axis], u1 = (lo[axis] + (k + 1) * w - a[axis]) / b[axis];
      if (u0 > u1) std::swap(u0, u1);
      const double f = std::min(t1, u1) - std::max(t0, u0);
      if (f > 0) accumulate(r[static_cast<std::size_t>(1 + k)], c, f);
    }
  }
};

}  // namespace grains::sim
