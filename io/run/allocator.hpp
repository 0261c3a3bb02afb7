#pragma once
// How the process asks the C library for memory (issue 26: memory per grain).

namespace grains::io {

/// Blocks of 4 MiB and more (a per-grain array from about 170,000 grains
/// on) are mapped from the kernel when allocated and returned to it when
/// freed; smaller ones reuse the heap as before. glibc's default raises
/// that threshold as large blocks are freed (up to 32 MiB), after which
/// the large temporaries of set-up and of each neighbour build stay in the
/// heap, resident, and the vectors carved from them are resident over their
/// whole capacity: 65 bytes per grain more in a settled bed of 10^6 grains
/// (bench/RESULTS.md). A fixed threshold of 128 KiB would do the same but
/// costs the 10k pour about 20 % in page faults at its frequent builds; the
/// heap keeps up to 8 MiB free at its top for the same reason.
/// Called once, first thing, by the command line and the Python module;
/// does nothing outside glibc.
/// (The heap's free pages go back to the kernel after set-up and after the
/// first neighbour build: sim/state/free_heap.hpp.)
void set_allocator_policy();

}  // namespace grains::io
