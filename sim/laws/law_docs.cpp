// Case-file keys of materials and of the contact law slots. The choices of
// each slot and each normal law's own keys come from the registries
// (normal_laws.hpp, contact_law.hpp), so a registered law is documented and
// accepted by the parser without an edit here.
#include <limits>
#include <set>

#include "sim/laws/contact_law.hpp"
#include "sim/laws/normal_laws.hpp"
#include "sim/keys/effect_doc.hpp"

namespace grains::sim {

std::vector<EffectDoc> law_docs() {
  const double inf = std::numeric_limits<double>::infinity();
  using K = KeyType;
  std::vector<EffectDoc> d;
  d.push_back({"materials", "materials: [ {...}, ... ]",
               "Material properties. A wall uses one too. Pair values are the arithmetic mean of the two "
               "materials unless contact.pairs overrides them.",
               {key("name", K::String, "name used by particles, walls and contact.pairs").req(),
                key("density", K::Number, "mass density").req().si("kg/m^3").in(0, inf, true),
                key("youngs_modulus", K::Number, "Young's modulus E").req().si("Pa").in(0, inf, true),
                key("poisson_ratio", K::Number, "Poisson ratio nu").req().in(-1, 0.5, true, true),
                key("restitution", K::Number,
                    "normal coefficient of restitution; the damping is calibrated so the clamped Hertz law "
                    "achieves it exactly")
                    .def(0.5).in(0, 1, true, false),
                key("friction", K::Number, "sliding (Coulomb) friction coefficient; 0 everywhere = frictionless")
                    .def(0.0).in(0, inf),
                key("rolling_friction", K::Number, "rolling friction coefficient of the EPSD rolling model")
                    .def(0.0).in(0, inf),
                key("cohesion_energy_density", K::Number, "SJKR cohesion energy density k_c").def(0.0).si("J/m^3").in(0, inf),
                key("surface_energy", K::Number,
                    "surface energy g of the adhesive normal laws (contact.model: dmt): a pair's work of adhesion "
                    "is 2 sqrt(g_a g_b), 2 g for one material")
                    .def(0.0)
                    .si("J/m^2")
                    .in(0, inf)}});
  // The slots' choices, from the registries.
  const std::vector<std::string> normals = type_names(NormalLaws{});
  std::vector<std::string> tangentials{"auto", "none"};
  std::set<std::string> seen;
  for_each_type(NormalLaws{}, [&]<class N>() {
    if (seen.insert(N::tangential_name).second) tangentials.push_back(N::tangential_name);
  });
  auto with_auto = [](std::vector<std::string> names) {
    names.insert(names.begin(), "auto");
    return names;
  };
  // One map of its own keys per normal law that has keys: contact.<law>: {...}.
  std::vector<KeySpec> law_maps;
  for_each_type(NormalLaws{}, [&]<class N>() {
    if (!N::keys().empty())
      law_maps.push_back(key(N::name, K::Map,
                             std::string("keys of the ") + N::name + " law (model: " + N::name + "; see contact." +
                                 N::name + ")"));
  });
  EffectDoc contact{"contact", "contact: {...}",
                    "The contact law: a normal law (contact.model) plus the tangential, rolling and cohesion slots. "
                    "'auto' switches a slot on when some material pair needs it; a slot that is off costs nothing. "
                    "The tangential spring is the one the normal law pairs with (mindlin with hertz, linear with "
                    "linear).",
                    {key("model", K::String, "normal law (see contact.<model>)").def(normals.front()).one_of(normals),
                     key("tangential", K::String, "tangential spring with history and Coulomb limit")
                         .def("auto")
                         .one_of(tangentials),
                     key("rolling", K::String, "rolling resistance (elastic-plastic spring, Ai et al. 2011)")
                         .def("auto")
                         .one_of(with_auto(type_names(RollingLaws{}))),
                     key("cohesion", K::String, "simplified JKR cohesion")
                         .def("auto")
                         .one_of(with_auto(type_names(CohesionLaws{}))),
                     key("pairs", K::List, "per material pair overrides (see contact.pairs)")}};
  for (const auto& k : law_maps) contact.keys.push_back(k);
  d.push_back(contact);
  EffectDoc pairs{"contact.pairs", "contact: { pairs: [ {...}, ... ] }",
                  "Values for one pair of materials instead of the mean of the two (and the normal law's own keys "
                  "for this pair, as a map named after the law).",
                  {key("materials", K::List, "the two material names, e.g. [glass, steel]").req(),
                   key("restitution", K::Number, "normal restitution").in(0, 1, true, false),
                   key("friction", K::Number, "sliding friction").in(0, inf),
                   key("rolling_friction", K::Number, "rolling friction").in(0, inf),
                   key("cohesion_energy_density", K::Number, "SJKR cohesion").si("J/m^3").in(0, inf),
                   key("work_of_adhesion", K::Number, "work of adhesion w of the adhesive normal laws")
                       .si("J/m^2")
                       .in(0, inf)}};
  for (const auto& k : law_maps) pairs.keys.push_back(k);
  d.push_back(pairs);
  for_each_type(NormalLaws{}, [&]<class N>() {
    d.push_back({std::string("contact.") + N::name,
                 std::string("contact: {model: ") + N::name + (N::keys().empty() ? "}" : ", " + std::string(N::name) + ": {...}}"),
                 N::summary(), N::keys()});
  });
  return d;
}

}  // namespace grains::sim
