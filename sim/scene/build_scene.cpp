#include "sim/scene/build_scene.hpp"

#include <cmath>
#include <sstream>

#include "sim/scene/placement.hpp"

namespace grains::sim {

namespace {
bool choose(SlotChoice c, bool automatic) { return c == SlotChoice::Auto ? automatic : c == SlotChoice::On; }
}  // namespace

SceneNeeds scene_needs(const SceneConfig& c, const PairTable& pairs) {
  SceneNeeds n;
  n.tangential = choose(c.tangential, pairs.any_friction());
  n.rolling = choose(c.rolling, pairs.any_rolling());
  n.cohesion = choose(c.cohesion, pairs.any_cohesion());
  n.rotation = n.tangential || n.rolling;
  n.gravity = c.gravity.squaredNorm() > 0;
  n.planes = !c.walls.planes.empty();
  n.cylinders = !c.walls.cylinders.empty();
  n.moving_walls = c.walls.max_displacement(1.0) > 0;
  n.history_size = (n.tangential ? 3 : 0) + (n.rolling ? 3 : 0);
  if (n.rotation) n.fields |= FieldSet(Field::AngularVelocity) | Field::Torque | Field::Inertia;
  if (n.history_size > 0 && c.walls.count() > 0) n.fields |= Field::WallHistory;
  return n;
}

double rayleigh_time(const SceneConfig& c) {
  double t = std::numeric_limits<double>::infinity();
  for (const auto& s : c.sets) {
    const Material& m = c.materials[s.material];
    const double r = s.placement.radii.empty() ? s.size.smallest()
                                               : *std::min_element(s.placement.radii.begin(), s.placement.radii.end());
    const double tr = M_PI * r * std::sqrt(m.density / m.shear_modulus()) / (0.1631 * m.poisson_ratio + 0.8766);
    t = std::min(t, tr);
  }
  return t;
}

Scene build_scene(SceneConfig& c) {
  Scene s;
  s.domain = c.domain;
  s.gravity = c.gravity;
  s.materials = c.materials;
  s.walls = c.walls;
  s.pairs = PairTable(c.materials, c.overrides);
  const SceneNeeds need = scene_needs(c, s.pairs);

  // Time step.
  const double tr = rayleigh_time(c);
  std::ostringstream msg;
  msg.precision(4);
  if (c.dt_rayleigh > 0) {
    c.dt = c.dt_rayleigh * tr;
  } else if (std::isfinite(tr)) {
    const double frac = c.dt / tr;
    if (frac > 1.0) {
      msg << c.dt_where << ": time step dt = " << c.dt << " s is " << frac
          << " Rayleigh times (T_R = " << tr << " s); above 1 the contacts are unresolved and the run would blow up."
          << " Use dt <= " << 0.3 * tr << " s (0.3 T_R) or give time.dt_rayleigh instead";
      throw SetupError(msg.str());
    }
    if (frac > 0.3) {
      msg << c.dt_where << ": warning: time step dt = " << c.dt << " s is " << frac
          << " Rayleigh times (T_R = " << tr << " s); above 0.3 the accuracy of contacts suffers";
      c.warnings.push_back(msg.str());
    }
  }
  s.clock.dt = c.dt;
  s.clock.end_time = c.end_time;
  s.clock.n_steps = static_cast<std::int64_t>(std::ceil(c.end_time / c.dt - 1e-9));

  // Walls get history slots when the law keeps history.
  int slot = 0;
  for (auto& w : s.walls.planes) w.history_slot = slot++;
  for (auto& w : s.walls.cylinders) w.history_slot = slot++;
  s.particles.configure(need.fields, slot * need.history_size);

  // Particles.
  const auto placed = place_particles(c);
  check_overlaps(c, placed);
  std::int64_t gid = 0;
  for (const auto& q : placed) {
    const auto& set = c.sets[q.set];
    const double m = c.materials[set.material].density * 4.0 / 3.0 * M_PI * q.r * q.r * q.r;
    if (!s.domain.contains(q.x)) {
      std::ostringstream e;
      e << set.where << ": particle " << q.index_in_set << " of set '" << set.name << "' at (" << q.x.transpose()
        << ") lies outside the domain; move it or enlarge domain";
      throw SetupError(e.str());
    }
    s.particles.add(gid++, q.x, set.velocity, q.r, m, set.material);
  }

  double rmax = 0;
  for (const auto r : s.particles.radius) rmax = std::max(rmax, r);
  s.neighbors.configure(need.history_size, c.skin * 2 * rmax);
  return s;
}

}  // namespace grains::sim
