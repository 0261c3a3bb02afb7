#pragma once
// Per-particle loops on OpenMP threads, only when threads run: with one
// thread the loop is a plain loop the compiler sees whole (an OpenMP region,
// even one that is switched off by an if clause, is an outlined function
// that costs vectorisation and register allocation).
#include <cstddef>

#include <omp.h>

namespace grains::sim {

/// True when loops of n iterations are worth splitting over threads.
inline bool use_threads(std::ptrdiff_t n, std::ptrdiff_t min_per_loop = 4096) {
  return n >= min_per_loop && omp_get_max_threads() > 1;
}

/// fn(i) for i in [0, n), on threads when `threads` is true. `flatten`
/// inlines fn into both loops (GCC would otherwise keep a large body called
/// from two places out of line: a call per particle).
template <class Fn>
__attribute__((flatten)) inline void parallel_for(bool threads, std::ptrdiff_t n, Fn&& fn) {
  if (threads) {
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < n; ++i) fn(i);
    return;
  }
  for (std::ptrdiff_t i = 0; i < n; ++i) fn(i);
}

}  // namespace grains::sim
