// Assembles the step pipeline from what the scene needs. The law slots are
// chosen here once, at run time, and each choice is a separate template
// instantiation, so the per-contact kernels carry no flags.
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

template <bool Rot>
void add_clear(Pipeline& p, bool gravity) {
  if (gravity)
    p.add(std::make_unique<ClearForces<Rot, true>>());
  else
    p.add(std::make_unique<ClearForces<Rot, false>>());
}

template <bool Rot>
void add_integrator(Pipeline& p, bool gravity) {
  p.add(std::make_unique<VerletDrift<Rot>>());
  add_clear<Rot>(p, gravity);
  p.add(std::make_unique<VerletKick<Rot>>());
}

}  // namespace

Pipeline assemble_pipeline(const Scene& s, const SceneConfig& c) {
  const SceneNeeds n = scene_needs(c, s.pairs);
  Pipeline p;
  if (n.ellipsoids) {
    p.add(std::make_unique<RigidBodyDrift>());
    add_clear<true>(p, n.gravity);
    p.add(std::make_unique<RigidBodyKick>());
  } else if (n.rotation) {
    add_integrator<true>(p, n.gravity);
  } else {
    add_integrator<false>(p, n.gravity);
  }
  if (n.moving_walls) p.add(std::make_unique<MoveWalls>());
  p.add(std::make_unique<NeighborStage>(c.sort_particles));
  if (n.tangential)
    dispatch_rolling<MindlinTangential>(p, n);
  else
    dispatch_rolling<NoTangential>(p, n);
  return p;
}

}  // namespace grains::sim
