#pragma once
// Mass output: at its cadence, one CSV row (OUTDIR/mass.csv) with the time,
// the number of grains and their mass on the front side of a plane (the
// whole domain by default), and the particles removed so far because they
// left the domain. Measures discharge: with the plane at a silo's orifice,
// the mass flow rate is minus the slope of mass_kg against time.
//
// A grain is a sphere, an ellipsoid or a whole clump (counted by its centre
// of mass, with the clump's mass); lost_particles counts removed particles
// (clump balls individually, as summary.json does).
// Case-file keys: output.mass (grains docs output.mass).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>

#include "sim/scene/stage.hpp"

namespace grains::io {

struct MassOutputConfig {
  bool enabled = false;
  std::int64_t every_steps = 0;  // 0: at the VTK frame cadence
  double every = 0;              // s (converted to steps at set-up)
  bool has_plane = false;        // count only grains with n . (x - point) > 0
  sim::Vec3 point{0, 0, 0}, normal{0, 0, 1};
};

struct MassCount {
  std::size_t grains = 0;
  double mass = 0;  // kg
};

/// Grains (spheres, ellipsoids, whole clumps) of the scene, and their mass,
/// whose centre lies on the front side of the plane (point, unit normal);
/// without a plane, all of them.
MassCount count_mass(const sim::Scene& s, const std::optional<std::pair<sim::Vec3, sim::Vec3>>& plane = {});

class MassOutput final : public sim::Stage {
 public:
  MassOutput(std::filesystem::path dir, MassOutputConfig cfg, std::int64_t every_steps);
  std::string name() const override;
  sim::Phase phase() const override { return sim::Phase::Output; }
  void run(sim::Scene& s) override;
  bool reads_state(const sim::Scene& s) const override { return every_ > 0 && s.clock.step % every_ == 0; }
  void finish(sim::Scene& s) override;
  void start(sim::Scene& s) override { write_row(s); }
  void restart(sim::Scene& s, const sim::RestartPoint&) override { resume(s); }
  /// Writes the row of the current state (the run writes the initial one).
  void write_row(const sim::Scene& s);
  /// After a restart: keeps the file's rows before the restored step, writes
  /// the restored state's row and appends after it.
  void resume(const sim::Scene& s);

 private:
  void open();
  std::filesystem::path file_;
  MassOutputConfig cfg_;
  std::int64_t every_;
  std::int64_t last_step_ = -1;
  std::ofstream out_;
};

}  // namespace grains::io
