// Case-file keys of the wall kinds, from the registry (wall_kinds.hpp): each
// kind's own keys between the ones every wall has.
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
    d.push_back(std::move(e));
  });
  return d;
}

}  // namespace grains::sim
