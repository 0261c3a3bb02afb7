#pragma once
// VTK XML output written through the VTK library: particles as one .vtu per
// frame (point data: id, radius, velocity, angular velocity when the scene
// rotates, force, coordination number, material; `body` in scenes with
// clumps), walls as .vtp, clump bodies as bodies_*.vtu (centre, orientation
// quaternion, principal axes axis_1..3 as vectors), and a .pvd time series
// for each that ParaView opens directly. The .pvd files are
// rewritten atomically after every frame, so an interrupted run leaves a
// valid series of the frames it wrote. Under MPI each rank writes its piece
// (frames/particles_NNNNNN_rRRRR.vtu) and rank 0 a .pvtu index per frame,
// which the .pvd lists, so ParaView opens the run as one dataset.
#include <filesystem>
#include <string>
#include <vector>

#include "sim/scene/stage.hpp"

namespace grains::io {

/// Per-particle coordination number (particle-particle contacts only).
std::vector<int> coordination_numbers(const sim::Scene& s);

class VtkOutput final : public sim::Stage {
 public:
  /// Frames every `every_steps` steps (0: first and last only).
  VtkOutput(std::filesystem::path dir, std::int64_t every_steps);
  std::string name() const override;
  sim::Phase phase() const override { return sim::Phase::Output; }
  void run(sim::Scene& s) override;
  bool reads_state(const sim::Scene& s) const override { return every_ > 0 && s.clock.step % every_ == 0; }
  void finish(sim::Scene& s) override;
  /// The frame of the initial state; after a restart, the series so far.
  void start(sim::Scene& s) override { write_frame(s); }
  void restart(sim::Scene& s, const sim::RestartPoint& r) override { resume(s, r.frame_times, r.frame_steps); }
  /// Writes a frame now (used for the initial state).
  void write_frame(const sim::Scene& s);
  std::size_t frames() const { return times_.size(); }
  /// The series so far (time and step of each frame), for checkpoints.
  const std::vector<double>& frame_times() const { return times_; }
  const std::vector<std::int64_t>& frame_steps() const { return steps_; }
  /// Continues a series after a restart: frames from a checkpoint; later
  /// frames of an interrupted run are overwritten as the run reaches them.
  /// Writes the frame of the current step if it is due and missing.
  void resume(const sim::Scene& s, std::vector<double> times, std::vector<std::int64_t> steps);

 private:
  // Each returns the array layout of the piece (for the .pvtu index).
  std::string write_particles(const sim::Scene& s, const std::filesystem::path& file) const;
  void write_walls(const sim::Scene& s, const std::filesystem::path& file) const;
  std::string write_bodies(const sim::Scene& s, const std::filesystem::path& file) const;
  void write_series(const sim::Scene& s) const;
  void write_pvd(const std::string& name, const std::string& prefix, const std::string& ext) const;
  std::filesystem::path dir_;
  std::int64_t every_;
  std::int64_t last_step_ = -1;
  mutable bool state_written_ = false;  // view.py (the ParaView state) written
  std::vector<double> times_;
  std::vector<std::int64_t> steps_;
};

}  // namespace grains::io
