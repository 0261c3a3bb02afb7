// Assembles the step pipeline from what the scene needs. The law slots are
// chosen here once, at run time, and each choice is a separate template
// instantiation, so the per-contact kernels carry no flags.
#include "sim/integrate/clump_bodies.hpp"
#include "sim/integrate/radius_growth.hpp"
#include "sim/integrate/rigid_body.hpp"
#include "sim/integrate/verlet.hpp"
#include "sim/laws/ellipsoid_pair_stage.hpp"
#include "sim/laws/pair_contact_stage.hpp"
#include "sim/neighbor/neighbor_stage.hpp"
#include "sim/scene/body_forces.hpp"
#include "sim/scene/build_scene.hpp"
#include "sim/walls/wall_contact_stage.hpp"

namespace grains::sim {

namespace {

template <class Law>
void add_contact_stages(Pipeline& p, const SceneNeeds& n) {
  if (n.ellipsoids) {
    p.add(std::make_unique<ShapePairContactStage<Law>>());
    if (n.planes) p.add(std::make_unique<PlaneWallStage<Law, true>>());
    if (n.cylinders) p.add(std::make_unique<CylinderWallStage<Law, true>>());
    return;
  }
  p.add(std::make_unique<PairContactStage<Law>>());
  if (n.planes) p.add(std::make_unique<PlaneWallStage<Law>>());
  if (n.cylinders) p.add(std::make_unique<CylinderWallStage<Law>>());
}

template <class T, class R>
void dispatch_cohesion(Pipeline& p, const SceneNeeds& n) {
  if (n.cohesion)
    add_contact_stages<ContactLaw<T, R, SjkrCohesion>>(p, n);
  else
    add_contact_stages<ContactLaw<T, R, NoCohesion>>(p, n);
}

template <class T>
void dispatch_rolling(Pipeline& p, const SceneNeeds& n) {
  if (n.rolling)
    dispatch_cohesion<T, EpsdRolling>(p, n);
  else
    dispatch_cohesion<T, NoRolling>(p, n);
}

template <bool Rot, bool Clumps = false>
void add_clear(Pipeline& p, bool gravity) {
  if (gravity)
    p.add(std::make_unique<ClearForces<Rot, true, Clumps>>());
  else
    p.add(std::make_unique<ClearForces<Rot, false, Clumps>>());
}

template <bool Rot, bool Clumps>
void add_integrator(Pipeline& p, bool gravity) {
  p.add(std::make_unique<VerletDrift<Rot, Clumps>>());
  add_clear<Rot, Clumps>(p, gravity);
  p.add(std::make_unique<VerletKick<Rot, Clumps>>());
}

template <bool Clumps>
void add_integrators(Pipeline& p, const SceneNeeds& n) {
  if (n.ellipsoids) {
    p.add(std::make_unique<RigidBodyDrift>());
    add_clear<true, Clumps>(p, n.gravity);
    p.add(std::make_unique<RigidBodyKick>());
  } else if (n.rotation) {
    add_integrator<true, Clumps>(p, n.gravity);
  } else {
    add_integrator<false, Clumps>(p, n.gravity);
  }
  // The bodies after the particles in each phase: they place their balls last.
  if constexpr (Clumps) {
    p.add(std::make_unique<ClumpDrift>());
    p.add(std::make_unique<ClumpKick>());
  }
}

}  // namespace

Pipeline assemble_pipeline(const Scene& s, const SceneConfig& c) {
  const SceneNeeds n = scene_needs(c, s.pairs);
  Pipeline p;
  if (n.clumps)
    add_integrators<true>(p, n);
  else
    add_integrators<false>(p, n);
  if (n.moving_walls) p.add(std::make_unique<MoveWalls>());
  if (c.growth.enabled) p.add(std::make_unique<RadiusGrowth>(c.growth));
  p.add(std::make_unique<NeighborStage>(c.sort_particles));
  if (n.tangential)
    dispatch_rolling<MindlinTangential>(p, n);
  else
    dispatch_rolling<NoTangential>(p, n);
  if (n.clumps) p.add(std::make_unique<ClumpForces>());  // last of the force phase
  return p;
}

}  // namespace grains::sim
