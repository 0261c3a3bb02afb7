#pragma once
// Gives the heap's free pages back to the kernel (glibc's malloc_trim).
// Blocks below the mmap threshold (4 MiB: io/run/allocator.hpp) come from the
// heap, and what they leave when freed stays resident until then. Called
// after set-up (2 million small blocks of a 10^6 bed's overlap check and
// positions file: 67 bytes per grain otherwise) and after the first neighbour
// build (io/run/simulation.cpp); and by a build of 2^17 grains or more before
// it allocates the contact history (sim/neighbor/neighbor_list.cpp), since
// its temporaries (about 8 MB at 10^6) made the build's peak 8 bytes per
// grain above the run's resident size: 407 -> 398 bytes per grain
// (bench/RESULTS.md). Not at every build of small scenes: the 10k pour would
// fault its build temporaries in again each time. Does nothing outside glibc.
#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace grains::sim {

/// The mmap threshold io/run/allocator.cpp sets: blocks this large come from
/// the kernel, faulted in page by page when first written.
inline constexpr unsigned long kMappedBlockBytes = 4ul << 20;

inline void release_free_heap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace grains::sim
