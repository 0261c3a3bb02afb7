#pragma once
// What a scene's particles hold in memory, by part (issue 26): every
// per-particle field, each part of the neighbour list and contact history,
// the walls' near lists, the ghost exchange's lists and buffers, and the
// clump bodies. Counted from the containers' sizes (what is in use, and so
// resident; room an array keeps beyond its size is never written), on this rank; summary.json gives them per particle
// beside the process's peak resident set size (docs/memory.md).
#include <string>
#include <utility>
#include <vector>

#include "sim/scene/scene.hpp"

namespace grains::sim {

struct MemoryPart {
  std::string name;   // "field:position", "contact_history", ...
  double bytes = 0;   // on this rank
};

/// The parts, fields first; the same list on every rank of a run (parts
/// may be zero), so that they can be summed part by part.
std::vector<MemoryPart> memory_parts(const Scene& s);

class Pipeline;
/// The scene's parts and then those the pipeline's stages hold (Stage::
/// memory_parts; stages' parts of the same name are summed).
std::vector<MemoryPart> memory_parts(const Scene& s, const Pipeline& pipeline);

/// The process's resident set size now (peak = false) or its peak (VmHWM),
/// in bytes, from /proc/self/status; 0 where that is not available.
double resident_bytes(bool peak);

}  // namespace grains::sim
