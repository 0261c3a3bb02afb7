// Case-file keys of the wall types, declared beside walls.hpp.
#include <limits>

#include "sim/scene/effect_doc.hpp"

namespace grains::sim {

std::vector<EffectDoc> wall_docs() {
  const double inf = std::numeric_limits<double>::infinity();
  using K = KeyType;
  std::vector<EffectDoc> d;
  d.push_back({"walls.plane", "walls: [ {type: plane, ...} ]",
               "An infinite plane; particles stay on the side its normal points to. Contacts use the same law "
               "as particle pairs with the wall as an infinitely heavy body. With hole_radius and/or radius the "
               "plane is finite: a zero-thickness annulus (a disc, or a plane with a circular hole such as a silo "
               "bottom with its orifice) about `point`, touched on both faces and on its rims; particles pass "
               "through the hole. An ellipsoid can touch it at two places at once (e.g. lying across the hole).",
               {key("type", K::String, "wall type").req().one_of({"plane", "cylinder"}),
                key("name", K::String, "label used in output"),
                key("point", K::Vec3, "a point on the plane; the centre of the hole and of the disc").req().si("m"),
                key("normal", K::Vec3, "normal towards the particles (normalised for you)").req(),
                key("hole_radius", K::Number, "radius of a circular hole about point (an orifice)")
                    .def("0").si("m").in(0, inf),
                key("radius", K::Number, "outer radius of a finite disc (> hole_radius)")
                    .def("infinite").si("m").in(0, inf, true),
                key("material", K::String, "material name").req(),
                key("velocity", K::Vec3, "constant prescribed velocity").def("[0, 0, 0]").si("m/s")}});
  d.push_back({"walls.cylinder", "walls: [ {type: cylinder, ...} ]",
               "The lateral surface of a finite circular cylinder (add planes for end caps).",
               {key("type", K::String, "wall type").req().one_of({"plane", "cylinder"}),
                key("name", K::String, "label used in output"),
                key("base", K::Vec3, "centre of the bottom end of the axis").req().si("m"),
                key("axis", K::Vec3, "axis direction (normalised for you)").def("[0, 0, 1]"),
                key("radius", K::Number, "radius of the surface").req().si("m").in(0, inf, true),
                key("height", K::Number, "length along the axis from base").req().si("m").in(0, inf, true),
                key("inside", K::Bool, "true: particles are held inside (a silo); false: kept outside (a post)").def("true"),
                key("material", K::String, "material name").req(),
                key("velocity", K::Vec3, "constant prescribed velocity").def("[0, 0, 0]").si("m/s")}});
  return d;
}

}  // namespace grains::sim
