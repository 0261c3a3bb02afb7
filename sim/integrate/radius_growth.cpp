#include "sim/integrate/radius_growth.hpp"

#include <algorithm>
#include <cmath>

#include "sim/parallel/exchange.hpp"

namespace grains::sim {

double RadiusGrowth::overlap_per_particle(const Scene& s) {
  const auto& p = s.particles;
  const auto& nl = s.neighbors;
  const std::size_t n = p.n_owned();
  const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
  // A pair with a ghost (periodic image, other rank) is seen from both of
  // its particles' owners: half each, so every physical pair counts once.
  double sum = 0;
  for (std::size_t i = 0; i < rows; ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const auto j = nl.partner[k];
      const double rs = p.radius[i] + p.radius[j];
      const double d2 = (p.x[i] - p.x[j]).squaredNorm();
      if (d2 < rs * rs) sum += (i < n && j < n ? 1.0 : 0.5) * (1.0 - std::sqrt(d2) / rs);
    }
  double count = static_cast<double>(n);
  if (s.exchange) {
    sum = s.exchange->comm().sum(sum);
    count = s.exchange->comm().sum(count);
  }
  return count > 0 ? sum / count : 0.0;
}

void RadiusGrowth::run(Scene& s) {
  auto& p = s.particles;
  // The growth since the list's last build is not known after a restart:
  // rebuild once before the first growth. Radii are measured against the
  // smallest radius at the start (a restart continues from the grown radii).
  if (!started_) {
    s.neighbors.add_growth(s.neighbors.skin());
    started_ = true;
  }
  if (!c_.phases.empty()) {  // the phase of the current time (after the last: radii fixed)
    const auto it = std::find_if(c_.phases.begin(), c_.phases.end(),
                                 [&](const GrowthPhase& ph) { return s.clock.time < ph.until; });
    const double rate = it == c_.phases.end() ? 0.0 : it->rate;
    const double target = it == c_.phases.end() ? c_.target_overlap : it->target_overlap;
    if (rate != c_.rate || target != c_.target_overlap) {
      c_.rate = rate;
      c_.target_overlap = target;
      rate_ = 0;
      last_measure_ = -1;  // measure now
    }
  }
  if (last_measure_ < 0 || s.clock.step - last_measure_ >= std::max<std::int64_t>(1, c_.every_steps)) {
    last_measure_ = s.clock.step;
    overlap_ = overlap_per_particle(s);
    rate_ = c_.rate == 0 ? 0.0 : c_.rate * std::clamp(1.0 - overlap_ / c_.target_overlap, -1.0, 1.0);
  }
  if (rate_ == 0) return;
  double f = std::exp(rate_ * s.clock.dt);
  // Growth stops at max_scale times the initial radii (the ghost cut-off of
  // periodic and parallel runs was sized for it).
  if (f > 1 && c_.max_scale > 0 && c_.initial_radius > 0 && p.n_owned() > 0) {
    double rmin = p.radius[0];
    for (std::size_t i = 1; i < p.n_owned(); ++i) rmin = std::min(rmin, p.radius[i]);
    if (s.exchange) rmin = s.exchange->comm().min(rmin);
    f = std::min(f, c_.max_scale * c_.initial_radius / rmin);
    capped_ = f <= 1;
  }
  if (f == 1) return;
  const double f3 = f * f * f;
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
