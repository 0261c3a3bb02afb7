// Case-file keys of materials and of the contact law slots, declared beside
// the laws (see normal_hertz.hpp, tangential.hpp, rolling.hpp, cohesion.hpp).
#include <limits>

#include "sim/scene/effect_doc.hpp"

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
                    .def("0.5").in(0, 1, true, false),
                key("friction", K::Number, "sliding (Coulomb) friction coefficient; 0 everywhere = frictionless")
                    .def("0").in(0, inf),
                key("rolling_friction", K::Number, "rolling friction coefficient of the EPSD rolling model")
                    .def("0").in(0, inf),
                key("cohesion_energy_density", K::Number, "SJKR cohesion energy density k_c").def("0").si("J/m^3").in(0, inf)}});
  d.push_back({"contact", "contact: {...}",
               "The contact law: Hertz normal force with calibrated damping, clamped at zero, plus slots. "
               "'auto' switches a slot on when some material pair needs it; a slot that is off costs nothing.",
               {key("model", K::String, "normal law").def("hertz").one_of({"hertz"}),
                key("tangential", K::String, "Mindlin tangential spring with history and Coulomb limit")
                    .def("auto").one_of({"auto", "none", "mindlin"}),
                key("rolling", K::String, "rolling resistance (elastic-plastic spring, Ai et al. 2011)")
                    .def("auto").one_of({"auto", "none", "epsd"}),
                key("cohesion", K::String, "simplified JKR cohesion").def("auto").one_of({"auto", "none", "sjkr"}),
                key("pairs", K::List, "per material pair overrides (see contact.pairs)")}});
  d.push_back({"contact.pairs", "contact: { pairs: [ {...}, ... ] }",
               "Values for one pair of materials instead of the mean of the two.",
               {key("materials", K::List, "the two material names, e.g. [glass, steel]").req(),
                key("restitution", K::Number, "normal restitution").in(0, 1, true, false),
                key("friction", K::Number, "sliding friction").in(0, inf),
                key("rolling_friction", K::Number, "rolling friction").in(0, inf),
                key("cohesion_energy_density", K::Number, "SJKR cohesion").si("J/m^3").in(0, inf)}});
  return d;
}

}  // namespace grains::sim
