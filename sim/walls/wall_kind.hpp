#pragma once
// What every wall kind shares, and what a kind supplies (docs/architecture.md:
// how to add a wall kind). A kind is a struct deriving from WallCommon with
//   kind, position_name        case-file type (walls[].type) and the name of its moving reference point
//   summary(), keys()          its documentation and case-file keys, besides type, name, material, velocity
//   from_keys(KeyReader&)      the wall from its keys (the parser reports errors with their location)
//   slots(ellipsoids)          history slots per particle (contacts a grain can have with it at once)
//   near_list(p, n, skin, shapes, out)
//                              the particles of [0, n) that may touch it before they move the skin
//                              (bounding radius + skin; rebuilt with the neighbour list)
//   contacts<Shapes>(p, i, held, emit)
//                              emit(geometry, slot) for each contact of particle i (sphere, or
//                              ellipsoid when Shapes), slot the history slot it continues (< 32);
//                              held(k): slot k holds history
//   touches(x, r), touches(ellipsoid)
//                              any contact at all (insertion obstacles, `grains analyze`)
//   translate(d), position()   prescribed motion and the checkpointed pose
//   cells(surface, centre, half)
//                              its quads for the walls .vtp of each frame (infinite kinds sized by the
//                              domain's centre and half diagonal)
//   record(), from_record(v)   the numbers that rebuild it from a frame (`grains analyze`)
// and one line in wall_kinds.hpp. The wall stage, near lists, history slots,
// ARKODE, the ordered gather, insertion obstacles, checkpoints, VTK output,
// the case parser, `grains docs` and `grains analyze` iterate the registry.
#include <array>
#include <string>
#include <vector>

#include "contact/contact_geometry.hpp"
#include "sim/keys/key_reader.hpp"

namespace grains::sim {

using contact::Vec3;

/// The part of a wall every kind has.
struct WallCommon {
  std::string name;
  int material = 0;
  Vec3 velocity{0, 0, 0};  // prescribed, constant
  /// The wall's history slots in each particle's wall-history field: from
  /// history_slot on, history_slots of them (set by build_scene from slots()).
  int history_slot = 0;
  int history_slots = 1;
};

/// A wall's surface for output: quads (4 point indices) into `points`.
struct WallSurface {
  std::vector<Vec3> points;
  std::vector<std::array<int, 4>> quads;
};

}  // namespace grains::sim
