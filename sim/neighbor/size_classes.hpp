#pragma once
// Size classes of a wide size distribution (docs/neighbor.md): when the
// largest radius exceeds 2.5 times the smallest, radii within a factor 2
// share a class (class k: [r_min 2^k, r_min 2^(k+1)), the last open above,
// at most 8); otherwise one class. Used by the neighbour lists' search and
// the initial overlap check, so that both split sizes alike.
#include <algorithm>
#include <cmath>

namespace grains::sim {

struct SizeClasses {
  double rmin = 0;
  int count = 1;

  SizeClasses(double smallest, double largest)
      : rmin(smallest),
        count(largest > 2.5 * smallest ? std::min(8, 1 + static_cast<int>(std::floor(std::log2(largest / smallest))))
                                       : 1) {}
  int of(double r) const {
    return count == 1 ? 0 : std::clamp(static_cast<int>(std::floor(std::log2(r / rmin))), 0, count - 1);
  }
};

}  // namespace grains::sim
