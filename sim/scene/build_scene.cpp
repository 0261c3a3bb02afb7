#include "sim/scene/build_scene.hpp"

#include <omp.h>

#include "sim/parallel/exchange.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include "contact/ellipsoid/ellipsoid.hpp"
#include "sim/insert/insertion_stage.hpp"
#include "sim/laws/contact_law.hpp"
#include "sim/laws/normal_laws.hpp"
#include "sim/scene/placement.hpp"
#include "sim/scene/shear_pressure_stage.hpp"
#include "sim/walls/wall_control_stage.hpp"
#include "sim/integrate/clump_bodies.hpp"

namespace grains::sim {

namespace {
// Uniformly distributed rotation (Shoemake's method).
Quat random_orientation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double u1 = u(rng), u2 = 2 * M_PI * u(rng), u3 = 2 * M_PI * u(rng);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  return Quat(a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), b * std::cos(u3)).normalized();
}
bool choose(SlotChoice c, bool automatic) { return c == SlotChoice::Auto ? automatic : c == SlotChoice::On; }

}  // namespace

void add_grain(Scene& s, const ParticleSetConfig& set, const Vec3& x, double r, const Quat& o, std::int64_t& gid,
               std::int64_t body_id, bool ellipsoid_fields, const std::string& what) {
  auto& p = s.particles;
  const double rho = s.materials[set.material].density;
  if (set.shape.kind == ShapeConfig::Kind::Clump) {
    // A clump of bounding radius r: a body and its balls. The balls' mass
    // field holds the body's mass (m* of their contacts).
    const ClumpShape& c = *set.shape.clump;
    const Eigen::Matrix3d R = o.toRotationMatrix();
    const double m = rho * c.volume * r * r * r;
    for (std::size_t k = 0; k < c.radii.size(); ++k) {
      const Vec3 xb = x + R * (r * c.centres[k]);
      if (!s.domain.contains(xb)) {
        std::ostringstream e;
        e << set.where << ": " << what << " of set '" << set.name << "' has a ball at (" << xb.transpose()
          << ") outside the domain; move it or enlarge domain";
        throw SetupError(e.str());
      }
    }
    s.bodies.add(body_id, x, set.velocity, o, m, rho * std::pow(r, 5) * c.inertia, c.volume * r * r * r,
                 static_cast<int>(c.radii.size()));
    for (std::size_t k = 0; k < c.radii.size(); ++k) {
      const Vec3 off = r * c.centres[k];
      const auto i = p.add(gid++, x + R * off, set.velocity, r * c.radii[k], m, set.material, kSphere);
      p.body[i] = body_id;
      p.body_offset[i] = off;
      if (ellipsoid_fields) p.orientation[i] = o;
    }
    return;
  }
  const bool ell = set.shape.kind == ShapeConfig::Kind::Ellipsoid;
  const Vec3 axes = r * set.shape.axes_rel;
  const double m = rho * 4.0 / 3.0 * M_PI * axes.prod();
  if (!s.domain.contains(x)) {
    std::ostringstream e;
    e << set.where << ": " << what << " of set '" << set.name << "' at (" << x.transpose()
      << ") lies outside the domain; move it or enlarge domain";
    throw SetupError(e.str());
  }
  const auto i = p.add(gid++, x, set.velocity, r, m, set.material, ell ? kEllipsoid : kSphere);
  if (set.frozen) p.inv_mass[i] = 0;  // held: what marks a frozen grain everywhere (checkpoints, ranks, ghosts)
  if (ellipsoid_fields) {
    p.semi_axes[i] = axes;
    const Vec3 a2 = axes.cwiseProduct(axes);
    p.inertia[i] = m / 5.0 * Vec3(a2.y() + a2.z(), a2.x() + a2.z(), a2.x() + a2.y());
    if (ell) {
      p.orientation[i] = o;
      p.form[i] = contact::quadratic_form(axes, o);
    }
  }
}

SceneNeeds scene_needs(const SceneConfig& c, const PairTable& pairs) {
  SceneNeeds n;
  n.tangential = choose(c.tangential, pairs.any_friction());
  n.rolling = choose(c.rolling, pairs.any_rolling());
  n.cohesion = choose(c.cohesion, pairs.any_cohesion());
  // Grains inserted during the run count as if they were there from the start.
  auto shapes = [&](const ParticleSetConfig& s) {
    n.ellipsoids = n.ellipsoids || s.shape.kind == ShapeConfig::Kind::Ellipsoid;
    n.clumps = n.clumps || s.shape.kind == ShapeConfig::Kind::Clump;
  };
  for (const auto& s : c.sets) shapes(s);
  for (const auto& ins : c.insertions) shapes(ins.grains);
  // The slots' laws by name, from their registries.
  auto pick = [](bool on, const std::string& asked, std::vector<std::string> names) {
    return !on ? std::string("none") : asked.empty() ? names.at(1) : asked;
  };
  n.rolling_law = pick(n.rolling, c.rolling_law, type_names(RollingLaws{}));
  n.cohesion_law = pick(n.cohesion, c.cohesion_law, type_names(CohesionLaws{}));
  n.tangential_history = n.tangential ? SpringTangential::history_size : 0;
  with_type_named(RollingLaws{}, n.rolling_law, [&]<class R>() { n.rolling_history = R::history_size; });
  n.rotation = n.tangential || n.rolling || n.ellipsoids;
  n.gravity = c.gravity.squaredNorm() > 0;
  n.walls = c.walls.count() > 0;
  n.moving_walls = c.walls.max_speed() > 0 || c.walls.controlled();
  with_type_named(NormalLaws{}, c.normal.name, [&]<class N>() { n.normal_history = normal_history<N>(); });
  n.history_size = n.tangential_history + n.rolling_history + n.normal_history;
  if (c.integrator == Integrator::Arkode && n.history_size > 0) {
    n.history_in_state = true;
    n.history_size *= 2;
  }
  if (n.rotation) n.fields |= FieldSet(Field::AngularVelocity) | Field::Torque | Field::Inertia;
  if (n.history_size > 0 && c.walls.count() > 0) n.fields |= Field::WallHistory;
  if (n.ellipsoids)
    n.fields |= FieldSet(Field::Orientation) | Field::AngularMomentum | Field::SemiAxes | Field::ShapeForm;
  if (n.clumps) n.fields |= Field::Body;
  return n;
}

double rayleigh_time(const SceneConfig& c) {
  double t = std::numeric_limits<double>::infinity();
  std::vector<const ParticleSetConfig*> sets;
  for (const auto& s : c.sets) sets.push_back(&s);
  for (const auto& ins : c.insertions) sets.push_back(&ins.grains);  // grains inserted later
  for (const auto* sp : sets) {
    const auto& s = *sp;
    const Material& m = c.materials[s.material];
    double r = s.placement.radii.empty() ? s.size.smallest()
                                         : *std::min_element(s.placement.radii.begin(), s.placement.radii.end());
    r *= s.shape.bounding_factor * s.shape.axes_rel.minCoeff();  // the smallest semi-axis
    // A clump: its smallest ball (the set's radius is the bounding radius).
    // The equal-volume sphere is not enough: contacts far from the centre of
    // mass and several balls touching at once stiffen the body's motion
    // (measured: a pour of cube clumps blows up at 0.2 T_R of the
    // equal-volume radius, docs/physics.md).
    if (s.shape.kind == ShapeConfig::Kind::Clump)
      r *= *std::min_element(s.shape.clump->radii.begin(), s.shape.clump->radii.end());
    const double tr = M_PI * r * std::sqrt(m.density / m.shear_modulus()) / (0.1631 * m.poisson_ratio + 0.8766);
    t = std::min(t, tr);
  }
  return t;
}

std::int64_t planned_particles(const SceneConfig& c, bool capped_only) {
  auto balls = [](const ParticleSetConfig& s) -> std::int64_t {
    return s.shape.kind == ShapeConfig::Kind::Clump ? static_cast<std::int64_t>(s.shape.clump->radii.size()) : 1;
  };
  std::int64_t n = 0;
  for (const auto& s : c.sets) {
    const std::int64_t count = s.placement.kind == Placement::Kind::File
                                   ? static_cast<std::int64_t>(s.placement.positions.size())
                                   : s.count;  // 0 for a lattice that fills its region: counted once placed
    n += count * balls(s);
  }
  for (const auto& in : c.insertions) {
    if (capped_only && in.every > 0 && in.times == 0) continue;
    std::int64_t events = 1;
    if (in.every > 0) {
      const double until = in.until > 0 ? in.until : c.end_time;
      events = static_cast<std::int64_t>(std::floor(std::max(0.0, until - in.at) / in.every)) + 1;
      if (in.times > 0) events = std::min(events, in.times);
    }
    n += events * in.grains.count * balls(in.grains);
  }
  return n;
}

double available_memory() {
  std::ifstream f("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (f >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return 0;
}

GrainExtremes grain_extremes(const SceneConfig& c) {
  GrainExtremes g;
  g.rayleigh_time = rayleigh_time(c);
  g.min_mass = g.min_radius = std::numeric_limits<double>::infinity();
  auto add = [&](const ParticleSetConfig& s) {
    const double rho = c.materials[s.material].density;
    double r = s.placement.radii.empty() ? s.size.smallest()
                                         : *std::min_element(s.placement.radii.begin(), s.placement.radii.end());
    const ShapeConfig& sh = s.shape;
    double mass = 0, curvature = 0;
    if (sh.kind == ShapeConfig::Kind::Clump) {
      mass = rho * sh.clump->volume * r * r * r;
      curvature = r * *std::min_element(sh.clump->radii.begin(), sh.clump->radii.end());
    } else {
      const Vec3 axes = r * sh.bounding_factor * sh.axes_rel;
      mass = rho * 4.0 / 3.0 * M_PI * axes.prod();
      // The smallest radius of curvature of an ellipsoid: b^2/a.
      curvature = axes.minCoeff() * axes.minCoeff() / axes.maxCoeff();
    }
    g.min_mass = std::min(g.min_mass, mass);
    g.min_radius = std::min(g.min_radius, curvature);
  };
  for (const auto& s : c.sets) add(s);
  for (const auto& ins : c.insertions) add(ins.grains);
  return g;
}

Scene build_scene(SceneConfig& c) {
  Scene s;
  s.domain = c.domain;
  s.gravity = c.gravity;
  s.materials = c.materials;
  s.walls = c.walls;
  try {
    s.pairs = PairTable(c.materials, c.overrides, c.normal);
  } catch (const std::invalid_argument& e) {
    throw SetupError(c.normal_where + ": " + e.what());
  }
  const SceneNeeds need = scene_needs(c, s.pairs);
  // A normal law whose contacts outlive touching (JKR) keeps a contact state
  // the ellipsoid stages, ARKODE's ODE state and the overlap-based cohesion
  // slot have no place for.
  if (need.normal_history > 0) {
    const std::string law = "contact.model " + c.normal.name;
    if (need.ellipsoids)
      throw SetupError(c.normal_where + ": " + law + " is a law of spheres (and clumps of spheres); this scene has "
                       "ellipsoids: use model dmt for adhesive ellipsoids");
    if (c.integrator == Integrator::Arkode)
      throw SetupError(c.normal_where + ": " + law + " keeps whether each contact holds in tension, which is not "
                       "part of ARKODE's state; use time.integrator: verlet (" + c.integrator_where + ")");
    if (need.cohesion)
      throw SetupError(c.normal_where + ": " + law + " is itself the adhesion; cohesion (sjkr, from "
                       "cohesion_energy_density) would act on top of it: give one or the other");
  }

  // Time step: against the time scale of the normal law.
  const GrainExtremes extremes = grain_extremes(c);
  StepScale scale;
  with_type_named(NormalLaws{}, c.normal.name, [&]<class N>() { scale = N::step_scale(s.pairs, extremes); });
  std::ostringstream msg;
  msg.precision(4);
  if (c.dt_rayleigh > 0) c.dt = c.dt_rayleigh * extremes.rayleigh_time;
  const double tr = scale.time;
  const bool rayleigh = scale.rayleigh;
  // dt_rayleigh (validated at most 1) needs no check against the Rayleigh time itself.
  if (std::isfinite(tr) && tr > 0 && !(rayleigh && c.dt_rayleigh > 0)) {
    const double frac = c.dt / tr;
    const std::string& where = c.dt_where;
    // (ARKODE adapts its steps to the contacts; dt only bounds them.)
    if (frac > scale.refuse && c.integrator == Integrator::Verlet) {
      msg << where << ": time step dt = " << c.dt << " s is " << frac << " " << scale.unit << " (" << scale.symbol
          << " = " << tr << " s); above " << scale.refuse
          << " the contacts are unresolved and the run would blow up. Use dt <= " << scale.warn * tr << " s ("
          << scale.warn << " " << scale.symbol << ")"
          << (rayleigh ? " or give time.dt_rayleigh instead" : "");
      throw SetupError(msg.str());
    }
    if (frac > scale.warn && c.integrator == Integrator::Verlet) {
      msg << where << ": warning: time step dt = " << c.dt << " s is " << frac << " " << scale.unit << " ("
          << scale.symbol << " = " << tr << " s); above " << scale.warn << " the accuracy of contacts suffers";
      c.warnings.push_back(msg.str());
    }
  }
  s.clock.dt = c.dt;
  s.clock.end_time = c.end_time;
  s.clock.n_steps = static_cast<std::int64_t>(std::ceil(c.end_time / c.dt - 1e-9));

  // Walls get history slots when the law keeps history.
  int slot = 0, tag = 0;
  s.walls.for_each([&](auto& w, std::size_t) {
    w.history_slot = slot;
    w.history_slots = w.slots(need.ellipsoids);
    slot += w.history_slots;
    if constexpr (std::decay_t<decltype(w)>::tagged) {
      w.tag_offset = tag;
      tag += 1 + 3 * w.history_slots;  // the mask of the slots held, and a normal per slot
    }
    if constexpr (requires { w.place(0.0); }) w.place(w.motion_time);  // its pose and velocities now
  });
  s.particles.configure(need.fields, slot * need.history_size, tag);

  // Memory, before anything is allocated per particle: the fields are exact;
  // the neighbour lists are estimated for a dense bed (4 list pairs per
  // particle: 3.6 measured in the settled 10k pour with the default skin,
  // 3.9 in the settled beds of bench/scale), each pair a partner index, its
  // history and a may-touch byte, plus the row start; twice, for the build
  // that holds the old list and the new one; plus the positions and ids of
  // the last build (docs/memory.md). A case whose fields
  // alone (per rank) exceed the memory available is refused here, not by
  // std::bad_alloc somewhere in the placement.
  s.memory.particles = planned_particles(c);
  s.memory.field_bytes = static_cast<double>(s.particles.record_bytes());
  s.memory.list_bytes = 2 * (4.0 * (4 + 1 + 8.0 * need.history_size) + 4) + 24 + 8;
  if (const double avail = available_memory(); avail > 0) {
    const double ranks = static_cast<double>(Comm::world().size());
    const std::int64_t certain = planned_particles(c, true);
    const double fields = static_cast<double>(certain) * s.memory.field_bytes / ranks;
    if (fields > avail) {
      // Located at the particle set or insertion that asks for the most.
      std::string where;
      std::int64_t most = -1;
      for (const auto& set : c.sets)
        if (set.count > most) most = set.count, where = set.where;
      for (const auto& in : c.insertions)
        if (in.grains.count > most) most = in.grains.count, where = in.where;
      std::ostringstream e;
      e.precision(3);
      e << (where.empty() ? "" : where + ": ") << "the case asks for " << certain
        << " particles: their fields alone need " << fields / 1073741824.0 << " GiB" << (ranks > 1 ? " per rank" : "") << " (" << s.memory.field_bytes
        << " bytes each), and the neighbour lists about " << s.memory.list_bytes << " bytes each more, but this "
        << "machine has " << avail / 1073741824.0 << " GiB available; lower the counts (particles[].count, "
        << "insert[].count or times) or run on more machines";
      throw SetupError(e.str());
    }
  }

  // Particles, into arrays of exactly their size (grown one by one, an
  // array of 10^7 grains would have a capacity of 2^24).
  const auto placed = place_particles(c);
  check_overlaps(c, placed);
  s.particles.visit_fields([&](const char*, const char*, auto& v, int width) {
    v.reserve(placed.size() * static_cast<std::size_t>(width));
  });
  std::int64_t gid = 0;
  std::vector<std::mt19937_64> orient_rng;
  for (const auto& set : c.sets) orient_rng.emplace_back(set.placement.seed ^ 0x9E3779B97F4A7C15ull);
  for (const auto& q : placed) {
    const auto& set = c.sets[q.set];
    // Orientations drawn as the set asks: clumps always, ellipsoids when the
    // scene has orientation fields (it does whenever there are ellipsoids).
    Quat o = set.shape.orientation;
    const bool clump = set.shape.kind == ShapeConfig::Kind::Clump;
    const bool ell = set.shape.kind == ShapeConfig::Kind::Ellipsoid;
    if ((clump || (ell && need.ellipsoids)) && set.shape.random_orientation) o = random_orientation(orient_rng[q.set]);
    const auto body_id = static_cast<std::int64_t>(s.bodies.size());
    add_grain(s, set, q.x, q.r, o, gid, body_id, need.ellipsoids,
              (clump ? "clump " : "particle ") + std::to_string(q.index_in_set));
  }
  if (c.growth.enabled) {
    c.growth.initial_radius = std::numeric_limits<double>::infinity();
    for (const auto& set : c.sets)
      c.growth.initial_radius =
          std::min(c.growth.initial_radius, set.placement.radii.empty()
                                                ? set.size.smallest()
                                                : *std::min_element(set.placement.radii.begin(), set.placement.radii.end()));
  }
  if (c.growth.enabled && (need.ellipsoids || need.clumps))
    throw SetupError(c.growth_where + ": radius_growth grows spheres only; this scene has " +
                     (need.ellipsoids ? "ellipsoids" : "clumps"));

  if (need.clumps) place_clump_balls(s.particles, s.bodies, true);
  // The positions a file gave are in the particles now: their copy in the
  // case (24 bytes and a line number per grain) goes. (The radii stay: the
  // Rayleigh time of the case is read from them.)
  for (auto& set : c.sets) {
    std::vector<Vec3>().swap(set.placement.positions);
    std::vector<std::int64_t>().swap(set.placement.position_line);
  }
  // Kinds that check themselves against the domain and the initial particles
  // (a mesh wall: its units, its place, particles starting inside it).
  s.walls.for_each([&](const auto& w, std::size_t) {
    if constexpr (requires { w.setup_error(s.domain.lo, s.domain.hi, s.particles, c.overlap_tolerance); }) {
      const std::string e = w.setup_error(s.domain.lo, s.domain.hi, s.particles, c.overlap_tolerance);
      if (!e.empty()) throw SetupError(e);
    }
  });
  setup_wall_controls(s, c.integrator == Integrator::Arkode, c.integrator_where);
  if (s.domain.shear.on()) {
    if (c.integrator == Integrator::Arkode)
      throw SetupError(c.shear_where + ": domain.shear (Lees-Edwards) moves its images by the Verlet step; use "
                       "time.integrator: verlet (" + c.integrator_where + ")");
    if (need.clumps)
      throw SetupError(c.shear_where + ": domain.shear (Lees-Edwards) does not take clumps yet (a body crossing the "
                       "sheared face would have to carry its balls' velocities)");
    setup_shear_pressure(s, c.shear_where);
    if (c.parallel.dims[s.domain.shear.flow] > 1)
      throw SetupError(c.parallel.where + ": with domain.shear the ranks may not split the flow axis " +
                       std::string(1, "xyz"[s.domain.shear.flow]) + " (its images are displaced along it): give 1 there");
    // On the mean flow from the start (frozen grains keep their set's velocity).
    if (c.shear_profile) {
      const int f = s.domain.shear.flow, g = s.domain.shear.gradient;
      const double yc = 0.5 * (s.domain.lo[g] + s.domain.hi[g]);
      auto& p = s.particles;
      for (std::size_t i = 0; i < p.n_owned(); ++i)
        if (p.inv_mass[i] > 0) p.v[i][f] += s.domain.shear.rate * (p.x[i][g] - yc);
    }
  }
  double rmax = 0;
  for (const auto r : s.particles.radius) rmax = std::max(rmax, r);
  // Grains inserted later: their largest sphere or ellipsoid radius, or clump ball.
  for (const auto& ins : c.insertions) {
    const auto& g = ins.grains;
    const double q = g.size.largest() * g.shape.bounding_factor;
    if (g.shape.kind == ShapeConfig::Kind::Clump)
      for (double rb : g.shape.clump->radii) rmax = std::max(rmax, q * rb);
    else
      rmax = std::max(rmax, q);
  }
  check_insertions(c);
  // Ellipsoid scenes keep the PW85 lambda of each pair after the law's history.
  s.neighbors.configure(need.history_size + (need.ellipsoids ? 1 : 0), c.skin * 2 * rmax);
  s.neighbors.set_frozen(c.has_frozen());
  if (c.skin_per_grain) s.neighbors.set_skin_fraction(c.skin);
  s.neighbors.set_image_speed(std::abs(s.domain.shear_speed()));
  // Contacts that hold beyond touching (JKR): the lists reach the largest
  // pull-off separation (R* is at most the largest radius, against a wall).
  const double grow = c.growth.enabled ? c.growth.max_scale : 1.0;
  with_type_named(NormalLaws{}, c.normal.name, [&]<class N>() {
    if constexpr (normal_history<N>() > 0) s.neighbors.set_reach(N::reach(s.pairs, rmax * grow));
  });
  setup_parallel(s, c, rmax);
  return s;
}

void setup_parallel(Scene& s, SceneConfig& c, double rmax) {
  // Threads: ordered, race-free force sums whenever more than one thread
  // runs, so results never depend on the thread count. Ranks: ordered sums
  // unless the case turns them off, so that results do not depend on the
  // decomposition and a checkpoint continues bitwise on the same rank count
  // (the continuation re-decomposes and rebuilds its lists). A serial run
  // sums in list order unless asked (its checkpoints keep the lists).
  // One thread unless OMP_NUM_THREADS asks for more (OpenMP would take every core).
  if (!std::getenv("OMP_NUM_THREADS")) omp_set_num_threads(1);
  const Comm& comm = Comm::world();
  const bool threads = omp_get_max_threads() > 1;
  s.deterministic = c.parallel.deterministic.value_or(comm.parallel()) || threads;
  if (threads && c.parallel.deterministic == false)
    c.warnings.push_back("parallel.deterministic: warning: false is ignored with " +
                         std::to_string(omp_get_max_threads()) +
                         " OpenMP threads: threads always sum the contact forces in order (OMP_NUM_THREADS=1 "
                         "for sums in list order)");
  s.neighbors.set_gather(s.deterministic);
  // Ordered sums hold, per list entry, both sides' force (and torques) and
  // the gather's order (and, in the sphere lanes' compact layout, each
  // entry's record: 4 bytes, counted for every kind), about 4 list entries
  // per grain in a dense bed, as in the estimate above (docs/memory.md).
  if (s.deterministic)
    s.memory.list_bytes += 4.0 * (2 * (s.particles.fields().has(Field::Torque) ? 6 : 3) * 8.0 + 2 * 4 + 4) + 4;
  if (!comm.parallel() && !s.domain.any_periodic()) return;
  // Ghost cut-off: the largest pair cut-off, plus how far a clump's ball may
  // lie from the centre of mass that decides its rank.
  double extent = 0;
  if (s.particles.fields().has(Field::Body))
    for (std::size_t i = 0; i < s.particles.n_owned(); ++i)
      if (s.particles.body[i] >= 0) extent = std::max(extent, s.particles.body_offset[i].norm());
  for (const auto& ins : c.insertions)  // clumps inserted later
    if (ins.grains.shape.kind == ShapeConfig::Kind::Clump) {
      const double q = ins.grains.size.largest() * ins.grains.shape.bounding_factor;
      for (const auto& cb : ins.grains.shape.clump->centres) extent = std::max(extent, q * cb.norm());
    }
  // Growing radii (radius_growth) reach at most max_scale times their start.
  const double grow = c.growth.enabled ? c.growth.max_scale : 1.0;
  const double cut = 2 * rmax * grow + s.neighbors.skin() + extent + s.neighbors.reach();
  ExchangeOptions opt;
  opt.dims = c.parallel.dims;
  if (s.domain.shear.on()) opt.dims[s.domain.shear.flow] = 1;  // images displaced along the flow: one rank holds it
  opt.balance_threshold = c.parallel.balance_threshold;
  opt.largest_radius = rmax * grow;  // the cut-off's 2 r_max: each grain's ghost goes as far as its own radius needs
  try {
    s.exchange = std::make_shared<Exchange>(comm, s.domain, cut, opt);
  } catch (const std::runtime_error& e) {
    throw SetupError(c.parallel.where.empty() ? std::string(e.what()) : c.parallel.where + ": " + e.what());
  }
  s.exchange->distribute_initial(s);
}

}  // namespace grains::sim
