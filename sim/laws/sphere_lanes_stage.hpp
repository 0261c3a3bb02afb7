#pragma once
// The force loop of PairContactStage for Hertz–Mindlin with its spring and
// nothing else (the common dry law), in lockstep lanes: the touching pairs
// of the list go into batches (sphere_lanes.hpp) and their forces are added
// as the scalar loop adds them. In its own translation unit, not in the
// stage's template: one copy, compiled once.
#include "sim/laws/entry_forces.hpp"
#include "sim/laws/sphere_lanes.hpp"

namespace grains::sim {

struct Scene;

/// The pair forces and torques of every list entry of s. Not deferred
/// (serial): added to the particles in list order, batch for the lanes.
/// Deferred (deterministic mode, threads): per-entry results into e in
/// parallel over rows, then the ordered gather (entry_forces.hpp) and the
/// stress probe if the step measures it.
void sphere_pair_lanes(Scene& s, SphereContactBatch& batch, EntryForces& e, bool deferred);

}  // namespace grains::sim
