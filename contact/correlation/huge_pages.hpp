#pragma once
// Large scratch arrays on transparent huge pages. The NUFFT touches arrays of
// tens of MB in scattered order (the sort's scatter of 10^6 points, the
// subgrids added into the fine grid); with 4 KiB pages nearly every such
// access misses the TLB. Arrays of at least kHugePageMin bytes are aligned to
// 2 MiB and marked MADV_HUGEPAGE, which Debian's default THP mode
// ("madvise") honours; smaller ones, and systems without madvise, get plain
// aligned memory. Nothing depends on the advice being taken.
#include <cstddef>
#include <new>

namespace grains::correlation {

inline constexpr std::size_t kHugePageMin = std::size_t{4} << 20;

// 64-byte aligned (2 MiB aligned and advised for huge pages from
// kHugePageMin bytes); throws std::bad_alloc. Free with free_large.
void* allocate_large(std::size_t bytes);
void free_large(void* p) noexcept;

template <class T>
struct LargeAllocator {
  using value_type = T;
  LargeAllocator() = default;
  template <class U>
  LargeAllocator(const LargeAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_large(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) noexcept { free_large(p); }
  template <class U>
  bool operator==(const LargeAllocator<U>&) const noexcept { return true; }
};

}  // namespace grains::correlation
