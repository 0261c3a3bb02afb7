#include "sim/integrate/radius_growth.hpp"

#include <algorithm>
#include <cmath>

namespace grains::sim {

double RadiusGrowth::overlap_per_particle(const Scene& s) {
  const auto& p = s.particles;
  const auto& nl = s.neighbors;
  const std::size_t n = p.n_owned();
  if (n == 0 || nl.row_start.size() < n + 1) return 0;
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const auto j = nl.partner[k];
      const double rs = p.radius[i] + p.radius[j];
      const double d2 = (p.x[i] - p.x[j]).squaredNorm();
      if (d2 < rs * rs) sum += 1.0 - std::sqrt(d2) / rs;
    }
  return sum / static_cast<double>(n);
}

void RadiusGrowth::run(Scene& s) {
  // The growth since the list's last build is not known after a restart:
  // rebuild once before the first growth.
  if (!started_) {
    s.neighbors.add_growth(s.neighbors.skin());
    started_ = true;
  }
  if (s.clock.step % std::max<std::int64_t>(1, c_.every_steps) == 0) {
    overlap_ = overlap_per_particle(s);
    rate_ = c_.rate * std::clamp(1.0 - overlap_ / c_.target_overlap, -1.0, 1.0);
  }
  if (rate_ == 0) return;
  auto& p = s.particles;
  const double f = std::exp(rate_ * s.clock.dt), f3 = f * f * f;
  double rmax = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // ghosts too: they are copies
    p.radius[i] *= f;
    p.mass[i] *= f3;
    p.inv_mass[i] /= f3;
    rmax = std::max(rmax, p.radius[i]);
  }
  if (p.fields().has(Field::Inertia))
    for (std::size_t i = 0; i < p.size(); ++i) p.inertia[i] *= f3 * f * f;
  if (f > 1) s.neighbors.add_growth(rmax * (1 - 1 / f));
  s.neighbors.refresh_pair_constants(p);
}

}  // namespace grains::sim
