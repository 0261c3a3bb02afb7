#include "io/run/allocator.hpp"

#include <cstdlib>  // defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace grains::io {

void set_allocator_policy() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 4 << 20);  // a fixed value also turns off the dynamic threshold
  // and leaves the trim threshold at 128 KiB, so the heap's top would be
  // given back and faulted in again at every neighbour build (6 % of the 10k
  // pour): twice the mmap threshold, as glibc's dynamic rule sets it.
  mallopt(M_TRIM_THRESHOLD, 8 << 20);
#endif
}

}  // namespace grains::io
