#pragma once
// Contacts recomputed from a frame's geometry (the output holds per-particle
// net forces, not pair forces): every pair whose shapes overlap, with the
// normal overlap, normal, contact point and effective radius R*. Spheres use
// the exact sphere-sphere overlap; ellipsoids (frames with semi_axes and
// orientation) use the PW85 contact geometry of contact/ellipsoid. Balls of
// the same clump (equal `body`) are not contacts.
//
// Coordination counts contacts per particle, or per clump when the frame
// holds clump balls (several ball-ball contacts between two clumps are one
// clump-clump contact), plus contacts with walls when the walls are known
// (walls.hpp). A rattler is a particle with fewer than `min_contacts` contacts
// (default 4 = d + 1, the fewest non-coplanar contacts that can hold a
// frictionless sphere; kept as the convention for frictional packings too,
// although friction can hold a grain with fewer). Two rules:
//  * once: particles with fewer than min_contacts contacts are rattlers;
//  * iterative (O'Hern et al. PRE 68, 2003, for frictionless jammed packings):
//    rattlers' contacts are removed and the test repeats until nothing changes.
// Z without rattlers is the mean, over non-rattlers, of their contacts with
// non-rattlers and walls.
#include <cstddef>
#include <vector>

#include "postprocess/frame.hpp"
#include "postprocess/packing_fraction.hpp"

namespace grains::postprocess {

struct Contact {
  std::size_t i = 0, j = 0;  // particle indices in the frame, i < j
  double overlap = 0;        // normal overlap (m); > 0 when touching
  Vec3 normal{0, 0, 1};      // from j towards i
  Vec3 point{0, 0, 0};
  double radius = 0;         // effective radius of curvature R*
};

struct ContactOptions {
  /// Pairs closer than touching by less than this gap (m) also count; 0 counts
  /// only overlapping pairs, as the simulation's own coordination output does.
  double gap = 0;
};

std::vector<Contact> find_contacts(const Frame& f, const ContactOptions& o = {});

/// Which unit (particle, or clump when the frame has `body`) each particle belongs to.
struct Units {
  std::vector<std::size_t> of;  // per particle
  std::size_t count = 0;
  std::vector<Vec3> centre;     // per unit: particle centre or mean of its balls
};
Units units_of(const Frame& f);

struct Coordination {
  std::vector<int> z;            // contacts per unit (with any unit and walls)
  std::vector<char> rattler;     // per unit
  std::vector<int> z_rigid;      // contacts per unit with non-rattlers (0 for rattlers)
  std::size_t n_selected = 0, n_rattlers = 0;
  double mean_z = 0;             // mean z over the selected units
  double mean_z_without_rattlers = 0;  // mean z_rigid over selected non-rattlers
  double rattler_fraction = 0;   // among the selected units
  std::vector<std::size_t> histogram;  // selected units with z = 0, 1, 2, ...
};

/// Units are selected when their centre lies in `region`; their contacts with
/// units outside the region count.
enum class RattlerRule { once, iterative };

/// `wall_z` (optional, per particle) are contacts with walls (wall_contacts()).
Coordination coordination(const Frame& f, const Units& u, const std::vector<Contact>& contacts, const Box& region,
                          int min_contacts = 4, RattlerRule rule = RattlerRule::once,
                          const std::vector<int>& wall_z = {});

}  // namespace grains::postprocess
