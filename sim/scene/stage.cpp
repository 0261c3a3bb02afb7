#include "sim/scene/stage.hpp"

#include <algorithm>

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
}

void Pipeline::run_phase(Scene& s, Phase p) {
  for (auto& st : stages_)
    if (st->phase() == p) st->run(s);
}

void Pipeline::initialize(Scene& s) {
  run_phase(s, Phase::Neighbor);
  run_phase(s, Phase::Force);
}

void Pipeline::step(Scene& s) {
  for (auto& st : stages_) {
    if (st->phase() == Phase::Output) {
      s.clock.step += 1;
      s.clock.time = static_cast<double>(s.clock.step) * s.clock.dt;
      for (auto& o : stages_)
        if (o->phase() == Phase::Output) o->run(s);
      return;
    }
    st->run(s);
  }
  s.clock.step += 1;
  s.clock.time = static_cast<double>(s.clock.step) * s.clock.dt;
}

void Pipeline::finish(Scene& s) {
  for (auto& st : stages_) st->finish(s);
}

std::vector<std::string> Pipeline::stage_names() const {
  std::vector<std::string> n;
  for (const auto& s : stages_) n.push_back(std::string(phase_name(s->phase())) + ": " + s->name());
  return n;
}

}  // namespace grains::sim
