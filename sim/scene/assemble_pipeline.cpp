// Assembles the step pipeline from what the scene needs. The law slots are
// chosen here once, at run time, and each choice is a separate template
// instantiation, so the per-contact kernels carry no flags.
#include <algorithm>
#include <cmath>

#include "sim/integrate/arkode.hpp"
#include "sim/integrate/clump_bodies.hpp"
#include "sim/integrate/history_state_law.hpp"
#include "sim/integrate/radius_growth.hpp"
#include "sim/integrate/rigid_body.hpp"
#include "sim/integrate/verlet.hpp"
#include "sim/laws/ellipsoid_pair_stage.hpp"
#include "sim/laws/pair_contact_stage.hpp"
#include "sim/insert/insertion_stage.hpp"
#include "sim/neighbor/neighbor_stage.hpp"
#include "sim/scene/body_forces.hpp"
#include "sim/scene/build_scene.hpp"
#include "sim/scene/shear_pressure_stage.hpp"
#include "sim/walls/wall_contact_stage.hpp"
#include "sim/walls/wall_control_stage.hpp"

namespace grains::sim {

namespace {

// (Laws whose contacts outlive touching, JKR, are for spheres and clumps
// only, with Verlet and no cohesion slot: build_scene refuses the rest, and
// those stages are not instantiated for them.)
template <class Law>
void add_contact_stages(Pipeline& p, const SceneNeeds& n) {
  if (n.ellipsoids) {
    if constexpr (holds_beyond_touching<Law>()) {
      throw SetupError(Law::name() + " has no ellipsoid contacts");
    } else {
      p.add(std::make_unique<ShapePairContactStage<Law>>());
      if (n.walls) p.add(std::make_unique<WallStage<Law, true>>());
    }
    return;
  }
  p.add(std::make_unique<PairContactStage<Law>>());
  if (n.walls) p.add(std::make_unique<WallStage<Law>>());
}

// With ARKODE the law's history is part of the ODE state (laws with history only).
template <class Law>
void add_law(Pipeline& p, const SceneNeeds& n) {
  if constexpr (holds_beyond_touching<Law>()) {
    if (n.history_in_state) throw SetupError(Law::name() + " keeps a contact state ARKODE does not integrate");
  } else if constexpr (Law::history_size > 0) {
    if (n.history_in_state) {
      add_contact_stages<HistoryInState<Law>>(p, n);
      return;
    }
  }
  add_contact_stages<Law>(p, n);
}

// The slots' laws by their registry names (SceneNeeds: "none" when off).
template <class N, class T, class R>
void dispatch_cohesion(Pipeline& p, const SceneNeeds& n) {
  if constexpr (normal_history<N>() > 0) {
    if (n.cohesion_law != "none") throw SetupError(std::string(N::name) + " takes no cohesion slot");
    add_law<ContactLaw<N, T, R, NoCohesion>>(p, n);
    return;
  }
  if (!with_type_named(CohesionLaws{}, n.cohesion_law, [&]<class C>() { add_law<ContactLaw<N, T, R, C>>(p, n); }))
    throw SetupError("unknown cohesion law '" + n.cohesion_law + "'");
}

template <class N, class T>
void dispatch_rolling(Pipeline& p, const SceneNeeds& n) {
  if (!with_type_named(RollingLaws{}, n.rolling_law, [&]<class R>() { dispatch_cohesion<N, T, R>(p, n); }))
    throw SetupError("unknown rolling law '" + n.rolling_law + "'");
}

// The contact stages of the scene's normal law (a name from the registry,
// sim/laws/normal_laws.hpp) and the slots it needs.
void add_contact_law(Pipeline& p, const SceneNeeds& n, const std::string& normal) {
  const bool known = with_type_named(NormalLaws{}, normal, [&]<class N>() {
    if (n.tangential)
      dispatch_rolling<N, SpringTangential>(p, n);
    else
      dispatch_rolling<N, NoTangential>(p, n);
  });
  if (!known) throw SetupError("unknown normal law '" + normal + "'");
}

template <bool Rot, bool Clumps = false>
void add_clear(Pipeline& p, bool gravity, std::shared_ptr<ForceStart> start = nullptr) {
  if (gravity)
    p.add(std::make_unique<ClearForces<Rot, true, Clumps>>(std::move(start)));
  else
    p.add(std::make_unique<ClearForces<Rot, false, Clumps>>(std::move(start)));
}

// `start_in_drift`: the drift starts the owned particles' forces (ForceStart:
// without clumps and with nothing between drift and force phase that
// changes a mass, radius growth).
template <bool Rot, bool Clumps>
void add_integrator(Pipeline& p, bool gravity, bool start_in_drift) {
  auto waiting = std::make_shared<WaitingKick>();  // the kick left to the next drift
  std::shared_ptr<ForceStart> start;
  if (!Clumps && start_in_drift) {
    start = std::make_shared<ForceStart>();
    start->gravity = gravity;
  }
  p.add(std::make_unique<VerletDrift<Rot, Clumps>>(waiting, start));
  add_clear<Rot, Clumps>(p, gravity, start);
  p.add(std::make_unique<VerletKick<Rot, Clumps>>(waiting));
}

template <bool Clumps>
void add_integrators(Pipeline& p, const SceneNeeds& n, bool start_in_drift) {
  if (n.ellipsoids) {
    p.add(std::make_unique<RigidBodyDrift>());
    add_clear<true, Clumps>(p, n.gravity);
    p.add(std::make_unique<RigidBodyKick>());
  } else if (n.rotation) {
    add_integrator<true, Clumps>(p, n.gravity, start_in_drift);
  } else {
    add_integrator<false, Clumps>(p, n.gravity, start_in_drift);
  }
  // The bodies after the particles in each phase: they place their balls last.
  if constexpr (Clumps) {
    p.add(std::make_unique<ClumpDrift>());
    p.add(std::make_unique<ClumpKick>());
  }
}

// ARKODE (integrate/arkode.hpp): one driver stage that moves particles,
// bodies and walls and runs the neighbour and force phases itself; the force
// phase starts as for Verlet (clear forces, gravity).
void add_arkode(Pipeline& p, const Scene& s, const SceneConfig& c, const SceneNeeds& n) {
  ArkodeLayout layout;
  layout.rigid = n.ellipsoids;
  layout.rotation = n.rotation && !n.ellipsoids;
  layout.clumps = n.clumps;
  layout.tangential_history = n.tangential_history;
  layout.rolling_history = n.rolling_history;
  layout.pw85_slot = n.ellipsoids;
  ArkodeScales scales;
  const auto& r = s.particles.radius;
  if (!r.empty()) scales.length = *std::min_element(r.begin(), r.end());
  const auto& m = s.particles.mass;
  if (!m.empty()) scales.mass = *std::min_element(m.begin(), m.end());
  // The scene's speed, as the blow-up check estimates it: the fastest initial
  // speed (inserted grains' too), the fall through the domain and the fastest wall; a scene where
  // nothing moves takes the speed of a radius per Rayleigh time.
  double v0 = c.fastest_insertion();
  for (std::size_t i = 0; i < s.particles.n_owned(); ++i) v0 = std::max(v0, s.particles.v[i].norm());
  scales.speed = v0 + std::sqrt(2 * s.gravity.norm() * (s.domain.hi - s.domain.lo).norm()) + s.walls.max_speed();
  if (!(scales.speed > 0)) {
    const double tr = rayleigh_time(c);
    scales.speed = std::isfinite(tr) && tr > 0 ? scales.length / tr : 1.0;
  }
  p.add(make_arkode_integrator(c.arkode, layout, scales, c.integrator_where));
  const bool rot = n.rotation || n.ellipsoids;
  if (rot && n.clumps)
    add_clear<true, true>(p, n.gravity);
  else if (rot)
    add_clear<true, false>(p, n.gravity);
  else if (n.clumps)
    add_clear<false, true>(p, n.gravity);
  else
    add_clear<false, false>(p, n.gravity);
}

}  // namespace

Pipeline assemble_pipeline(const Scene& s, const SceneConfig& c) {
  const SceneNeeds n = scene_needs(c, s.pairs);
  Pipeline p;
  if (c.integrator == Integrator::Arkode)
    add_arkode(p, s, c, n);
  else if (n.clumps)
    add_integrators<true>(p, n, false);
  else
    add_integrators<false>(p, n, !c.growth.enabled);
  if (n.moving_walls && c.integrator == Integrator::Verlet) p.add(std::make_unique<MoveWalls>());
  if (s.walls.controlled()) p.add(std::make_unique<ControlWalls>());
  if (s.domain.shear.servo()) p.add(std::make_unique<ShearPressure>());
  if (c.growth.enabled) {
    if (c.integrator != Integrator::Verlet)
      throw SetupError("radius_growth (isotropic compression) runs with the Verlet integrator only; remove "
                       "time.integrator: arkode or the growth");
    p.add(std::make_unique<RadiusGrowth>(c.growth));
  }
  p.add(std::make_unique<NeighborStage>(c.sort_particles));
  add_contact_law(p, n, c.normal.name);
  if (c.has_frozen() && (n.rotation || n.ellipsoids)) p.add(std::make_unique<FrozenHold>());
  if (n.clumps) p.add(std::make_unique<ClumpForces>());  // last of the force phase
  // First of the output phase (outputs are added after it), only when asked for.
  if (!c.insertions.empty()) p.add(std::make_unique<InsertionStage>(c.insertions, s.clock.dt, n.ellipsoids));
  return p;
}

}  // namespace grains::sim
