#include "sim/scene/stage.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace grains::sim {

const char* phase_name(Phase p) {
  switch (p) {
    case Phase::Drift: return "drift";
    case Phase::Neighbor: return "neighbor";
    case Phase::Force: return "force";
    case Phase::Kick: return "kick";
    case Phase::Output: return "output";
  }
  return "?";
}

void Pipeline::add(std::unique_ptr<Stage> s) {
  // Keep phase order; within a phase, insertion order.
  const Phase ph = s->phase();
  auto it = std::find_if(stages_.begin(), stages_.end(), [ph](const auto& t) { return t->phase() > ph; });
  stages_.insert(it, std::move(s));
  seconds_.assign(stages_.size(), 0.0);
  driver_ = -1;
  int kicks = 0;
  for (std::size_t k = 0; k < stages_.size(); ++k) {
    if (stages_[k]->is_driver()) {
      if (driver_ >= 0) throw std::logic_error("a pipeline takes one driver stage");
      driver_ = static_cast<int>(k);
    }
    if (stages_[k]->phase() == Phase::Kick && kicks++ == 0) waiter_ = static_cast<int>(k);
  }
  if (kicks != 1 || driver_ >= 0 || !stages_[static_cast<std::size_t>(waiter_)]->can_wait()) waiter_ = -1;
}

void Pipeline::run_timed(std::size_t k, Scene& s) {
  // Exclusive times: what a stage spends in stages it runs itself (a driver
  // evaluating the force phase) is booked to those stages only.
  const double outer = nested_;
  nested_ = 0;
  const auto t0 = std::chrono::steady_clock::now();
  if (static_cast<int>(k) == driver_)
    stages_[k]->drive(s, *this);
  else
    stages_[k]->run(s);
  const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  seconds_[k] += dt - nested_;
  nested_ = outer + dt;
}

void Pipeline::run_phase(Scene& s, Phase p) {
  for (std::size_t k = 0; k < stages_.size(); ++k)
    if (stages_[k]->phase() == p) run_timed(k, s);
}

void Pipeline::initialize(Scene& s) {
  // The forces at t0 only: no time passes, so the contact history (springs of
  // pairs touching at t0) must not advance; the first step advances it.
  const double dt = s.clock.dt;
  s.clock.dt = 0;
  run_phase(s, Phase::Neighbor);
  run_phase(s, Phase::Force);
  s.clock.dt = dt;
}

void Pipeline::step(Scene& s, bool may_wait) {
  std::size_t k = 0;
  if (driver_ >= 0) {
    run_timed(static_cast<std::size_t>(driver_), s);
    while (k < stages_.size() && stages_[k]->phase() != Phase::Output) ++k;
  }
  if (may_wait && waiter_ >= 0) {
    // The kick phase is one stage that can wait, and it reads the clock's dt
    // only: the clock moves first, so that the output stages can say whether
    // they read the state at the step it now shows.
    for (; k < stages_.size() && stages_[k]->phase() != Phase::Kick; ++k) run_timed(k, s);
    s.clock.step += 1;
    s.clock.time = static_cast<double>(s.clock.step) * s.clock.dt;
    const bool read = std::any_of(stages_.begin() + k + 1, stages_.end(), [&](const auto& o) { return o->reads_state(s); });
    if (read)
      run_timed(k, s);
    else
      stages_[k]->wait(s);
    ++k;
  } else {
    for (; k < stages_.size() && stages_[k]->phase() != Phase::Output; ++k) run_timed(k, s);
    s.clock.step += 1;
    s.clock.time = static_cast<double>(s.clock.step) * s.clock.dt;
  }
  for (; k < stages_.size(); ++k) run_timed(k, s);
}

void Pipeline::settle(Scene& s) {
  for (auto& st : stages_) st->settle(s);
}

void Pipeline::start(Scene& s) {
  for (auto& st : stages_) st->start(s);
}

void Pipeline::restart(Scene& s, const RestartPoint& r) {
  for (auto& st : stages_) st->restart(s, r);
}

void Pipeline::finish(Scene& s) {
  settle(s);
  for (auto& st : stages_) st->finish(s);
}

std::vector<std::string> Pipeline::stage_names() const {
  std::vector<std::string> n;
  for (const auto& s : stages_) n.push_back(std::string(phase_name(s->phase())) + ": " + s->name());
  return n;
}

}  // namespace grains::sim
