#include "sim/integrate/radius_growth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/parallel/exchange.hpp"

namespace grains::sim {

double RadiusGrowth::overlap_per_particle(const Scene& s) {
  const auto& p = s.particles;
  const auto& nl = s.neighbors;
  const std::size_t n = p.n_owned();
  const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
  // A pair with a ghost (periodic image, other rank) is seen from both of
  // its particles' owners: half each, so every physical pair counts once.
  // Each term 1 - d/(ri + rj) lies in (0, 1]; summed as an integer number of
  // 2^-62 (exact and associative), the total does not depend on the order of
  // the pairs, so neither on the list nor on the ranks. Resolution 2^-63 per
  // term, far below the 1e-16 relative rounding of a double sum.
  __int128 sum = 0;
  for (std::size_t i = 0; i < rows; ++i)
    for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
      const auto j = nl.partner[k];
      const double rs = p.radius[i] + p.radius[j];
      const double d2 = (p.x[i] - p.x[j]).squaredNorm();
      if (d2 < rs * rs)
        sum += static_cast<std::int64_t>(std::ldexp(1.0 - std::sqrt(d2) / rs, i < n && j < n ? 62 : 61));
    }
  std::int64_t count = static_cast<std::int64_t>(n);
  if (s.exchange) {
    // Two 32-bit-aligned halves summed over ranks as int64 (no overflow below
    // 2^31 touching pairs per rank), then joined again.
    std::vector<std::int64_t> v{static_cast<std::int64_t>(sum >> 32), static_cast<std::int64_t>(sum & 0xffffffff),
                                count};
    s.exchange->comm().sum_in_place(v);
    sum = (static_cast<__int128>(v[0]) << 32) + v[1];
    count = v[2];
  }
  return count > 0 ? std::ldexp(static_cast<double>(sum), -62) / static_cast<double>(count) : 0.0;
}

void RadiusGrowth::run(Scene& s) {
  auto& p = s.particles;
  GrowthServo& g = s.growth;
  // The growth since the list's last build is not known at the start of a
  // run: rebuild once before the first growth (a restart restores it with
  // the list's build state and the servo, and does not rebuild). Radii are
  // measured against the smallest radius at the start.
  if (!g.started) {
    s.neighbors.add_growth(s.neighbors.skin());
    g.started = true;
    g.phase_rate = c_.rate;
    g.phase_target = c_.target_overlap;
  }
  if (!c_.phases.empty()) {  // the phase of the current time (after the last: radii fixed)
    const auto it = std::find_if(c_.phases.begin(), c_.phases.end(),
                                 [&](const GrowthPhase& ph) { return s.clock.time < ph.until; });
    const double rate = it == c_.phases.end() ? 0.0 : it->rate;
    const double target = it == c_.phases.end() ? g.phase_target : it->target_overlap;
    if (rate != g.phase_rate || target != g.phase_target) {
      g.phase_rate = rate;
      g.phase_target = target;
      g.rate = 0;
      g.last_measure = -1;  // measure now
    }
  }
  if (g.last_measure < 0 || s.clock.step - g.last_measure >= std::max<std::int64_t>(1, c_.every_steps)) {
    g.last_measure = s.clock.step;
    g.overlap = overlap_per_particle(s);
    g.rate = g.phase_rate == 0 ? 0.0 : g.phase_rate * std::clamp(1.0 - g.overlap / g.phase_target, -1.0, 1.0);
  }
  capped_ = g.capped;
  if (g.rate == 0) return;
  double f = std::exp(g.rate * s.clock.dt);
  // Growth stops at max_scale times the initial radii (the ghost cut-off of
  // periodic and parallel runs was sized for it).
  if (f > 1 && c_.max_scale > 0 && c_.initial_radius > 0 && p.n_owned() > 0) {
    double rmin = p.radius[0];
    for (std::size_t i = 1; i < p.n_owned(); ++i) rmin = std::min(rmin, p.radius[i]);
    if (s.exchange) rmin = s.exchange->comm().min(rmin);
    f = std::min(f, c_.max_scale * c_.initial_radius / rmin);
    g.capped = capped_ = f <= 1;
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
}

}  // namespace grains::sim
