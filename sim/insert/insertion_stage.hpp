#pragma once
// The insertion effect (case file: insert[]): at the times a case asks for,
// new grains are placed where they overlap nothing (insert_grains.hpp) and
// added to the particle store (and the body store for clumps). A scene
// without insert[] has no such stage.
//
// The stage sits at the start of the output phase: the grains it adds are in
// the frame and the checkpoint of the same step, and the neighbour lists are
// invalidated so that the next step rebuilds them (with migration and
// ghosts). Which steps insert is a function of the step number alone, and
// each insertion is seeded from the case's seed and its own index, so a run
// restarted from a checkpoint inserts exactly what the uninterrupted run does.
//
// MPI: every rank sends its grains to rank 0, which computes the insertion
// (the same result for any rank count: the grains are ordered by global id)
// and broadcasts the new grains; global ids continue from the largest id in
// use, in the order of placement, and each rank adds the grains whose centre
// (centre of mass) it owns. New grains start with zero force: their first
// half-kick misses gravity's g dt/2.
#include <vector>

#include "sim/insert/insert_grains.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {

class InsertionStage final : public Stage {
 public:
  /// `ellipsoid_fields`: the scene keeps orientations, semi-axes and forms.
  InsertionStage(std::vector<InsertionConfig> entries, double dt, bool ellipsoid_fields);
  std::string name() const override;
  Phase phase() const override { return Phase::Output; }
  void run(Scene& s) override;
  bool reads_state(const Scene& s) const override {  // it inserts at this step
    for (std::size_t e = 0; e < entries_.size(); ++e)
      if (event_at(e, s.clock.step) >= 0) return true;
    return false;
  }
  std::string summary_json() const override;

  struct Totals {
    int events = 0;
    insert::InsertStats last;
    std::int64_t requested = 0, placed = 0, trials = 0;
    double seconds = 0;
  };
  const std::vector<Totals>& totals() const { return totals_; }

 private:
  struct Schedule {
    std::int64_t first = 1, every = 0, last = 0, times = 0;  // times: events at most (0: no limit)
  };
  /// Index of the insertion entry e does at step n, or -1.
  std::int64_t event_at(std::size_t e, std::int64_t n) const;
  void insert_now(Scene& s, std::size_t e, std::int64_t event);
  std::vector<InsertionConfig> entries_;
  std::vector<Schedule> sched_;
  std::vector<Totals> totals_;
  bool ellipsoid_fields_;
};

/// Set-up checks of insert[] against the rest of the scene (integrator,
/// region inside the domain and large enough). Throws SetupError.
void check_insertions(const SceneConfig& c);

/// The grains of the scene as insertion sees them: every rank's owned
/// grains, on rank 0 (collective; the other ranks get an empty set), in
/// global-id order.
insert::SceneGrains gather_scene_grains(const Scene& s);

}  // namespace grains::sim
