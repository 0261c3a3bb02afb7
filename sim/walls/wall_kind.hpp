#pragma once
// What every wall kind shares, and what a kind supplies (docs/architecture.md:
// how to add a wall kind). A kind is a struct deriving from WallCommon with
//   kind, position_name        case-file type (walls[].type) and the name of its moving reference point
//   summary(), keys()          its documentation and case-file keys, besides type, name, material, velocity
//   from_keys(KeyReader&)      the wall from its keys (the parser reports errors with their location)
//   slots(ellipsoids)          history slots per particle (contacts a grain can have with it at once)
//   near(x, reach)             may a particle at x with bounding radius + skin = reach touch it?
//   contacts<Shapes>(p, i, c, held)
//                              the contacts of particle i (sphere, or ellipsoid when Shapes), each
//                              with the history slot it continues; held(k): slot k holds history
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

/// Up to two simultaneous contacts of one particle with one wall.
struct WallContacts {
  static constexpr int kMax = 2;
  int count = 0;
  contact::ContactGeometry g[kMax];
  int slot[kMax] = {0, 1};  // history slot of g[k], distinct, < the wall's history_slots
};

/// A wall's surface for output: quads (4 point indices) into `points`.
struct WallSurface {
  std::vector<Vec3> points;
  std::vector<std::array<int, 4>> quads;
};

/// How a registered kind reads its own case-file keys; io's case parser
/// implements it against the kind's doc(), so every error is located and
/// every range checked. Missing keys give the declared default, else `fallback`.
class KeyReader {
 public:
  virtual ~KeyReader() = default;
  virtual bool has(const std::string& key) const = 0;
  virtual double number(const std::string& key, double fallback) = 0;
  virtual Vec3 vec3(const std::string& key, const Vec3& fallback) = 0;
  virtual bool boolean(const std::string& key, bool fallback) = 0;
  /// Records an error at the key's location (the map's when absent).
  virtual void error(const std::string& key, const std::string& message) = 0;
  /// A unit direction from a vector key: a zero vector is an error.
  Vec3 direction(const std::string& key, const Vec3& fallback) {
    Vec3 v = vec3(key, fallback);
    if (v.norm() == 0) {
      error(key, key + " must not be the zero vector");
      v = fallback;
    }
    return v.normalized();
  }
};

}  // namespace grains::sim
