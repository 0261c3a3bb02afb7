#pragma once
// HDF5 checkpoints: the full state of a run, enough for a bitwise-exact
// continuation (layout in docs/checkpoint.md).
//
// What is saved: every allocated per-particle field (generically, through
// ParticleStore::visit_fields), the neighbour list with its contact history
// and build state (so that the continued run builds its lists at exactly
// the same steps and sums forces in exactly the same order), the moving wall
// states, the clock, the lost-particle count, the case (text as read and the
// effective YAML after --set) and the VTK series written so far. The run
// loop draws no random numbers, so there is no generator state to save.
//
// Files are written atomically: a hidden temporary in the same folder,
// flushed and fsync'ed, renamed over the final name, and the folder fsync'ed.
// A crash at any moment leaves either the previous checkpoint set or the new
// one, never a partial file under a checkpoint name.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/parallel/id_blocks.hpp"
#include "sim/scene/scene.hpp"

namespace grains::io {

/// Everything saved besides the scene.
struct CheckpointExtras {
  std::string case_path;       // the case file the run was started from
  std::string case_text;       // as read
  std::string case_effective;  // YAML after --set overrides
  std::vector<double> frame_times;        // VTK series so far (s)
  std::vector<std::int64_t> frame_steps;
  /// The cut planes of the rank grid (runs on several MPI ranks; empty
  /// otherwise): a continuation on the same grid takes them over.
  std::array<std::vector<double>, 3> cuts;
  /// Particle fields the checkpoint lacked, started as a new particle's (a
  /// stage without their effect: FieldInfo::restart_fresh).
  std::vector<std::string> fresh_fields;
};

/// Thrown for a checkpoint that cannot be written or read, or that does not
/// fit the case it is restarted with.
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Writes the scene (owned particles only) to `file` atomically.
void write_checkpoint(const std::filesystem::path& file, sim::Scene& s, const CheckpointExtras& extras);

/// True when checkpoints of runs on several MPI ranks are written with
/// parallel HDF5 (MPI-IO): HDF5 has it, and $GRAINS_CHECKPOINT_IO is unset
/// or `mpiio`; `gather` writes them from rank 0 (gather_scene) instead.
/// Throws CheckpointError for another value.
bool parallel_checkpoint_io();

/// Collective (every rank of MPI_COMM_WORLD): writes the run's state with
/// parallel HDF5, each rank its block `b` (sim::id_blocks) at its offsets,
/// into the same layout and content as write_checkpoint of gather_scene's
/// scene. `extras` must be the same on every rank (they come from the case
/// and the step count). Atomic as write_checkpoint: all ranks write a
/// hidden temporary, flush (MPI_File_sync on every rank) and close it;
/// then rank 0 fsyncs, renames and fsyncs the folder. A failure on any rank
/// throws the same CheckpointError on all of them (after the temporary is
/// removed).
void write_checkpoint_parallel(const std::filesystem::path& file, sim::Scene& s, sim::IdBlock& b,
                               const CheckpointExtras& extras);

/// Restores a checkpoint into a scene built from the same case (same
/// fields, law slots, walls and time step): particles, neighbour list,
/// history, walls, clock. The case's end time may differ (a run can be
/// extended). Throws CheckpointError saying what does not fit.
CheckpointExtras read_checkpoint(const std::filesystem::path& file, sim::Scene& s);

/// Step and time of a checkpoint without reading the state; throws when the
/// file is not a complete grains checkpoint.
struct CheckpointInfo {
  std::int64_t step = 0;
  double time = 0;
  std::size_t particles = 0;
};
CheckpointInfo checkpoint_info(const std::filesystem::path& file);

// ---- files in a checkpoint folder ----

/// "checkpoint_000000012000.h5" for step 12000.
std::string checkpoint_name(std::int64_t step);
/// Checkpoints in `dir` by step, oldest first (names only; not validated).
std::vector<std::filesystem::path> list_checkpoints(const std::filesystem::path& dir);
/// The newest checkpoint in `dir` that opens and is complete; empty when
/// none. Invalid ones are reported in `skipped` (path: reason).
std::filesystem::path newest_valid_checkpoint(const std::filesystem::path& dir,
                                              std::vector<std::string>* skipped = nullptr);
/// Removes all but the newest `keep` checkpoints, and leftover temporaries.
void prune_checkpoints(const std::filesystem::path& dir, int keep);
/// Removes checkpoints of steps after `step` (a restart from an older one
/// makes them a stale future); returns the removed names.
std::vector<std::string> remove_checkpoints_after(const std::filesystem::path& dir, std::int64_t step);

}  // namespace grains::io
