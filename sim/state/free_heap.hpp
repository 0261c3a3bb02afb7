#pragma once
// Gives the heap's free pages back to the kernel (glibc's malloc_trim).
// Blocks below the mmap threshold (4 MiB: io/run/allocator.hpp) come from the
// heap, and what they leave when freed stays resident until then: a neighbour
// build of 10^6 grains frees about 8 MB of such temporaries (its cell starts
// and counting-sort offsets) just before it allocates the contact history,
// which made the build's peak 8 bytes per grain above the run's resident size.
// Does nothing outside glibc.
#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace grains::sim {

inline void release_free_heap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace grains::sim
