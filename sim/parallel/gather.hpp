#pragma once
// The whole state of a decomposed (or periodic) run as one serial scene on
// rank 0: every rank's owned particles in global-id order, the bodies, and
// the contact histories as a neighbour list over those particles holding the
// pairs that have history. The list is marked stale (no build positions), so
// a run continuing from it rebuilds at its first step and carries the
// histories over by global ids. Checkpoints of parallel runs are written
// from it, and read back on any number of ranks.
#include "sim/scene/scene.hpp"

namespace grains::sim {

/// Collective: every rank must call it. Rank 0 gets the gathered scene,
/// the others an empty one (no particles).
Scene gather_scene(Scene& s);

}  // namespace grains::sim
