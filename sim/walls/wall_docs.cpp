// Case-file keys of the wall kinds, from the registry (wall_kinds.hpp): each
// kind's own keys between the ones every wall has.
#include <limits>

#include "sim/keys/effect_doc.hpp"
#include "sim/walls/wall_kinds.hpp"

namespace grains::sim {

std::vector<EffectDoc> wall_docs() {
  using K = KeyType;
  std::vector<std::string> kinds;
  for_each_type(WallKinds{}, [&]<class W>() { kinds.push_back(W::kind); });
  std::vector<EffectDoc> d;
  for_each_type(WallKinds{}, [&]<class W>() {
    EffectDoc e{std::string("walls.") + W::kind, std::string("walls: [ {type: ") + W::kind + ", ...} ]",
                W::summary(),
                {key("type", K::String, "wall type").req().one_of(kinds), key("name", K::String, "label used in output")}};
    for (auto& k : W::keys()) e.keys.push_back(std::move(k));
    e.keys.push_back(key("material", K::String, "material name").req());
    e.keys.push_back(key("velocity", K::Vec3, "constant prescribed velocity").def("[0, 0, 0]").si("m/s"));
    if (W::controllable)
      e.keys.push_back(key("control", K::Map, "a servo holding a stress or force, or a strain rate (see walls.control)"));
    d.push_back(std::move(e));
  });
  const double inf = std::numeric_limits<double>::infinity();
  std::string kinds_controlled;
  for_each_type(WallKinds{}, [&]<class W>() {
    if (W::controllable) kinds_controlled += (kinds_controlled.empty() ? "" : ", ") + std::string(W::kind);
  });
  d.push_back(EffectDoc{
      "walls.control", "walls: [ {type: plane, ..., control: {stress: 1e5, max_speed: 0.01}} ]",
      "A wall (" + kinds_controlled + ") moved along a direction by a controller instead of a prescribed velocity; "
      "a plane along its normal, a mesh along `direction`. Give one of stress, force or strain_rate. A servo "
      "(stress or force) holds the normal load F the grains put on the wall at its target F* (stress x area): after "
      "each step's forces, v = gain (F* - F) / (K dt + C), clamped to +-max_speed, where K and C are the sums of "
      "the normal stiffnesses and dashpots of the wall's contacts; the wall moves at v over the next step (towards the grains when v > 0; "
      "at max_speed when it touches nothing). The area is the box's cross-section when not given, measured each "
      "step: periodic lengths and the gaps between facing infinite planes (a triaxial box whose walls all move), or "
      "the disc of a cylinder wall along the direction (a die). A strain rate moves a plane at rate x L, L the "
      "distance to the plane facing it (> 0 compresses). wall_loads.csv then has each wall's speed, area and "
      "stress. Verlet only; under MPI the loads are summed over the ranks.",
      {key("stress", K::Number, "target normal stress on the wall, compressive > 0").si("Pa"),
       key("force", K::Number, "target normal force on the wall, compressive > 0 (instead of stress)").si("N"),
       key("strain_rate", K::Number, "prescribed strain rate (planes): speed = rate x the sample's length; > 0 "
                                     "compresses").si("1/s"),
       key("area", K::Number, "the area the stress acts on; default the box's cross-section, measured each step")
           .si("m^2")
           .in(0, inf, true),
       key("max_speed", K::Number, "the servo's speed limit (required with stress or force)").si("m/s").in(0, inf, true),
       key("gain", K::Number, "fraction of the load error the wall's contact springs take out per step")
           .def(0.5)
           .in(0, 1, true),
       key("direction", K::Vec3, "direction of motion towards the grains (mesh walls; a plane uses its normal)")}});
  return d;
}

}  // namespace grains::sim
