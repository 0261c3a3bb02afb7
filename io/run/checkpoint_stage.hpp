#pragma once
// The output stage that writes periodic checkpoints (io/checkpoint) and the
// final one at the end of a run, and the emergency save used by the run loop
// when a signal arrives or an output fails.
#include <filesystem>
#include <string>

#include "io/checkpoint/checkpoint.hpp"
#include "sim/scene/stage.hpp"

namespace grains::io {

class BlowUpCheck;
class VtkOutput;

class CheckpointStage final : public sim::Stage {
 public:
  /// every_steps = 0: no periodic checkpoints (only save_now()).
  CheckpointStage(std::filesystem::path dir, std::int64_t every_steps, int keep, CheckpointExtras case_info);
  std::string name() const override;
  sim::Phase phase() const override { return sim::Phase::Output; }
  void run(sim::Scene& s) override;
  bool reads_state(const sim::Scene& s) const override { return every_ > 0 && s.clock.step % every_ == 0; }
  /// The final checkpoint, when periodic checkpoints are on.
  void finish(sim::Scene& s) override;

  /// The series and the blow-up check the checkpoint consults (either may be null).
  void attach(const VtkOutput* vtk, BlowUpCheck* blow_up) {
    vtk_ = vtk;
    blow_up_ = blow_up;
  }
  /// Writes a checkpoint of the current step into the folder (unless one of
  /// this step was just written); returns its path. Refuses (BlowUp) a state
  /// that fails the blow-up diagnosis, so a good checkpoint is never pruned
  /// in favour of a bad one. Throws CheckpointError when it cannot write.
  std::filesystem::path save_now(sim::Scene& s);
  /// The same into another folder, without pruning (the fallback when the
  /// output folder cannot take it).
  std::filesystem::path save_to(sim::Scene& s, const std::filesystem::path& dir);
  /// Whether the full update before saving a decomposed or periodic run
  /// sorts particles by cell (the case's sort_particles).
  void set_sort(bool sort) { sort_ = sort; }
  /// Tells the stage which checkpoint the run continues from.
  void restarted_from(const std::filesystem::path& file, std::int64_t step);
  void restart(sim::Scene& s, const sim::RestartPoint& r) override { restarted_from(r.checkpoint, s.clock.step); }

  const std::filesystem::path& dir() const { return dir_; }
  const std::filesystem::path& last() const { return last_; }
  std::int64_t every_steps() const { return every_; }

 private:
  CheckpointExtras extras(const sim::Scene& s) const;
  std::filesystem::path dir_;
  std::int64_t every_;
  int keep_;
  CheckpointExtras case_info_;
  const VtkOutput* vtk_ = nullptr;
  BlowUpCheck* blow_up_ = nullptr;
  std::filesystem::path last_;
  std::int64_t last_step_ = -1;
  bool sort_ = true;
  std::int64_t updated_step_ = -1;  // step of the last full update before a save
};

}  // namespace grains::io
