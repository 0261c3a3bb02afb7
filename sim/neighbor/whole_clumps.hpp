#pragma once

#include <cstddef>
#include <vector>

namespace grains::sim {

struct Scene;

// A clump leaves as a whole: extends the flags `out` (one per owned
// particle) to every ball of a body that has a flagged ball, and drops those
// bodies from the scene. Returns how many flags it added. The particles
// themselves stay for the caller to remove (ParticleStore::remove_if).
std::size_t flag_whole_clumps(Scene& s, std::vector<char>& out);

}  // namespace grains::sim
