#pragma once
// Transparent huge pages for the large arrays a neighbour build allocates
// afresh (issue 26). A block of 4 MiB or more comes straight from the
// kernel (io/run/allocator.hpp) and is faulted in when first written: one
// fault per 4 KiB page, which on a virtual machine costs several
// microseconds each. Advised as huge before it is written, it faults in
// 2 MiB at a time. Only where the kernel's transparent huge pages are in
// "madvise" or "always" mode; elsewhere (and outside Linux) nothing changes.
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "sim/state/free_heap.hpp"

namespace grains::sim {

/// Advises [p, p + bytes) as huge pages, the 2 MiB-aligned part of it, when
/// it is a mapped block (kMappedBlockBytes or more). Not yet written pages
/// then fault in whole 2 MiB pages.
inline void advise_huge(void* p, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
  if (bytes < kMappedBlockBytes) return;
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t lo = (a + huge - 1) & ~(huge - 1), hi = (a + bytes) & ~(huge - 1);
  if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
#else
  (void)p, (void)bytes;
#endif
}

/// v.assign(n, value), into a fresh block advised as huge before it is
/// written when v's own block is too small (what assign would reallocate).
template <class T>
void assign_huge(std::vector<T>& v, std::size_t n, const T& value) {
  if (v.capacity() < n && n * sizeof(T) >= kMappedBlockBytes) {
    std::vector<T>().swap(v);
    v.reserve(n);
    advise_huge(v.data(), n * sizeof(T));
  }
  v.assign(n, value);
}

/// v.reserve(n) for an empty v, the block advised as huge.
template <class T>
void reserve_huge(std::vector<T>& v, std::size_t n) {
  if (v.empty() && v.capacity() < n && n * sizeof(T) >= kMappedBlockBytes) {
    std::vector<T>().swap(v);
    v.reserve(n);
    advise_huge(v.data(), n * sizeof(T));
  }
  v.reserve(n);
}

}  // namespace grains::sim
