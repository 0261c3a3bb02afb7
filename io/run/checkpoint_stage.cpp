#include "io/run/checkpoint_stage.hpp"

#include "io/output/progress.hpp"
#include "io/output/vtk_output.hpp"
#include "sim/parallel/comm.hpp"
#include "sim/parallel/exchange.hpp"
#include "sim/parallel/gather.hpp"
#include "sim/neighbor/neighbor_stage.hpp"
#include "sim/parallel/id_blocks.hpp"

namespace grains::io {

namespace fs = std::filesystem;

CheckpointStage::CheckpointStage(fs::path dir, std::int64_t every_steps, int keep, CheckpointExtras case_info)
    : dir_(std::move(dir)), every_(every_steps), keep_(keep), case_info_(std::move(case_info)) {}

std::string CheckpointStage::name() const {
  return "output.checkpoint(" +
         (every_ > 0 ? "every " + std::to_string(every_) + " steps, keep " + std::to_string(keep_)
                     : std::string("on signals only")) +
         ")";
}

void CheckpointStage::run(sim::Scene& s) {
  if (reads_state(s)) save_now(s);  // its cadence
}

void CheckpointStage::finish(sim::Scene& s) {
  if (every_ > 0) save_now(s);
}

void CheckpointStage::restarted_from(const fs::path& file, std::int64_t step) {
  last_ = file;
  last_step_ = step;
  if (blow_up_) blow_up_->set_last_good_checkpoint(file.string());
}

CheckpointExtras CheckpointStage::extras(const sim::Scene& s) const {
  CheckpointExtras x = case_info_;
  if (s.exchange && s.exchange->comm().parallel()) x.cuts = s.exchange->decomposition().cuts();
  if (vtk_) {
    x.frame_times = vtk_->frame_times();
    x.frame_steps = vtk_->frame_steps();
  }
  return x;
}

fs::path CheckpointStage::save_to(sim::Scene& s, const fs::path& dir) {
  const auto& comm = sim::Comm::world();
  if (blow_up_) {
    std::string bad = blow_up_->diagnose(s);
    if (comm.agree_error(bad))
      throw BlowUp(bad + (last_.empty() ? std::string(". No checkpoint was written before it")
                                        : ". The last good checkpoint is " + last_.string() + " (kept)"));
  }
  const fs::path file = dir / checkpoint_name(s.clock.step);
  if (!s.exchange) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw CheckpointError("cannot create checkpoint folder '" + dir.string() + "': " + ec.message());
    write_checkpoint(file, s, extras(s));
    return file;
  }
  // Decomposed or periodic runs: histories are keyed by global ids and
  // particles sorted by them, so any rank count can read the file back.
  // A continuation from the file wraps periodic positions, migrates and
  // rebuilds its lists at its first step; the run does the same here, at
  // the checkpoint's step, so that both continue from the same state (a
  // wrap rounds: x + L is not exact). The cuts in force after it are saved.
  if (updated_step_ != s.clock.step) {  // once per step (a fallback folder saves the same state)
    sim::NeighborStage::full_update(s, sort_, true);
    updated_step_ = s.clock.step;
  }
  std::string err;
  if (comm.parallel() && parallel_checkpoint_io()) {
    // Parallel HDF5: each rank writes its block of the global-id order.
    if (comm.root()) {
      std::error_code ec;
      fs::create_directories(dir, ec);
      if (ec) err = "cannot create checkpoint folder '" + dir.string() + "': " + ec.message();
    }
    if (comm.agree_error(err)) throw CheckpointError(err);
    auto block = sim::id_blocks(s);
    write_checkpoint_parallel(file, s, block, extras(s));  // throws the same error on every rank
    return file;
  }
  // Otherwise the whole state is gathered on rank 0, which writes it. Every
  // rank learns whether the write succeeded.
  auto whole = sim::gather_scene(s);
  if (comm.root()) {
    try {
      std::error_code ec;
      fs::create_directories(dir, ec);
      if (ec) throw CheckpointError("cannot create checkpoint folder '" + dir.string() + "': " + ec.message());
      write_checkpoint(file, whole, extras(s));
    } catch (const std::exception& e) {
      err = e.what();
    }
  }
  if (comm.agree_error(err)) throw CheckpointError(err);
  return file;
}

fs::path CheckpointStage::save_now(sim::Scene& s) {
  if (last_step_ == s.clock.step && !last_.empty() && fs::exists(last_)) return last_;
  last_ = save_to(s, dir_);
  last_step_ = s.clock.step;
  if (blow_up_) blow_up_->set_last_good_checkpoint(last_.string());
  if (sim::Comm::world().root()) prune_checkpoints(dir_, keep_);
  return last_;
}

}  // namespace grains::io
