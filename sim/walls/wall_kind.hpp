#pragma once
// What every wall kind shares, and what a kind supplies (docs/architecture.md:
// how to add a wall kind). A kind is a struct deriving from WallCommon with
//   kind, position_name        case-file type (walls[].type) and the name of its moving reference point
//   controllable               whether it takes walls[].control (wall_control.hpp)
//   summary(), keys()          its documentation and case-file keys, besides type, name, material, velocity
//   from_keys(KeyReader&)      the wall from its keys (the parser reports errors with their location)
//   slots(ellipsoids)          history slots per particle (contacts a grain can have with it at once)
//   near_list(p, n, skin, shapes, out, items)
//                              the particles of [0, n) that may touch it before they move the skin
//                              (bounding radius + skin; rebuilt with the neighbour list), and for
//                              each what the kind wants at hand (items: a mesh's near triangles;
//                              such a kind sets near_items = true)
//   contacts<Shapes>(p, i, items, slots, emit)
//                              emit(geometry, slot) for each contact of particle i (sphere, or
//                              ellipsoid when Shapes), slot the history slot it continues (< 32;
//                              -1: none free, no history); slots.held(k): slot k holds history,
//                              slots.keeps_history(), slots.tag(k) (tagged kinds); spheres are
//                              looked for with radius slots.grown(r) (a law whose contacts hold
//                              beyond touching, JKR, grows it by its reach; the stage corrects the
//                              overlap)
//   touches(x, r), touches(ellipsoid)
//                              any contact at all (insertion obstacles, `grains analyze`)
//   translate(d), position()   prescribed motion and the checkpointed pose (a kind with its own
//                              motion has advance(dt) and motion_time, checkpointed too)
//   surface_velocity(q), max_speed()
//                              (WallCommon's: the constant velocity) for a kind whose surface
//                              moves otherwise (rotation)
//   cells(surface, centre, half)
//                              its quads for the walls .vtp of each frame (infinite kinds sized by the
//                              domain's centre and half diagonal)
//   record(), from_record(v)   the numbers that rebuild it from a frame (`grains analyze`)
// and one line in wall_kinds.hpp. The wall stage, near lists, history slots,
// ARKODE, the ordered gather, insertion obstacles, checkpoints, VTK output,
// the case parser, `grains docs` and `grains analyze` iterate the registry.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "contact/contact_geometry.hpp"
#include "sim/keys/key_reader.hpp"
#include "sim/walls/wall_control.hpp"

namespace grains::sim {

using contact::Vec3;

/// The part of a wall every kind has.
struct WallCommon {
  std::string name;
  std::string where;  // its place in the case file (file:line), for messages
  int material = 0;
  Vec3 velocity{0, 0, 0};  // prescribed, constant (a controlled wall: set by its control each step)
  /// A controlled motion along a direction (wall_control.hpp); none by default.
  WallControl control;
  /// The wall's history slots in each particle's wall-history field: from
  /// history_slot on, history_slots of them (set by build_scene from slots()).
  int history_slot = 0;
  int history_slots = 1;
  /// Kinds whose slots carry a tag (tagged = true: the contact's normal, 3
  /// doubles per slot in ParticleStore::wall_tags) start at this offset there.
  int tag_offset = 0;
  static constexpr bool tagged = false;
  /// Kinds whose near list carries items per listed particle (near_items =
  /// true: a mesh's near triangles, NearItems), which contacts() receives.
  static constexpr bool near_items = false;

  /// Defaults a kind may replace: its surface's velocity at a point, a bound
  /// on any of its points' speed.
  Vec3 surface_velocity(const Vec3&) const { return velocity; }
  double max_speed() const { return velocity.norm(); }
};

/// A wall's surface for output: quads and triangles (point indices) into `points`.
struct WallSurface {
  std::vector<Vec3> points;
  std::vector<std::array<int, 4>> quads;
  std::vector<std::array<int, 3>> triangles;
};

/// What a kind's near list holds besides the particles, per listed particle
/// (a mesh: the triangles near it): items[start[m], start[m + 1]) for the
/// m-th particle of the list. Empty (start = {0}) for kinds without.
struct NearItems {
  std::vector<std::uint32_t> start{0};
  std::vector<std::uint32_t> items;
  bool operator==(const NearItems&) const = default;
};

}  // namespace grains::sim
