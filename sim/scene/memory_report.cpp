#include "sim/scene/memory_report.hpp"

#include <algorithm>
#include <fstream>
#include <type_traits>

#include "sim/parallel/exchange.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {

namespace {

// In use: an array's room beyond its size is never written, so it is not
// resident (an array that grew by doubling has up to as much again).
template <class V>
double bytes(const V& v) {
  return static_cast<double>(v.size() * sizeof(typename V::value_type));
}

}  // namespace

std::vector<MemoryPart> memory_parts(const Scene& s) {
  std::vector<MemoryPart> out;
  auto add = [&](std::string name, double b) { out.push_back({std::move(name), b}); };
  const ParticleStore& p = s.particles;
  p.declare_fields([&](const ParticleStore::FieldInfo& f, auto member, auto) { add(std::string("field:") + f.name, bytes(p.*member)); });
  for (const auto& [name, b] : s.neighbors.memory_parts()) add(name, static_cast<double>(b));
  if (s.exchange) add("ghost_exchange", static_cast<double>(s.exchange->memory_bytes()));
  const BodyStore& c = s.bodies;
  add("clump_bodies", bytes(c.id) + bytes(c.x) + bytes(c.v) + bytes(c.orientation) + bytes(c.angular_momentum) +
                          bytes(c.omega) + bytes(c.mass) + bytes(c.volume) + bytes(c.inertia) + bytes(c.members) +
                          bytes(c.force) + bytes(c.torque));
  return out;
}

std::vector<MemoryPart> memory_parts(const Scene& s, const Pipeline& pipeline) {
  std::vector<MemoryPart> out = memory_parts(s);
  const std::size_t scene_parts = out.size();
  for (const auto& stage : pipeline.stages())
    for (auto& [name, b] : stage->memory_parts()) {
      auto same = std::find_if(out.begin() + static_cast<std::ptrdiff_t>(scene_parts), out.end(),
                               [&](const MemoryPart& m) { return m.name == name; });
      if (same == out.end())
        out.push_back({std::move(name), b});
      else
        same->bytes += b;
    }
  return out;
}

double resident_bytes(bool peak) {
  std::ifstream f("/proc/self/status");
  std::string key;
  const std::string want = peak ? "VmHWM:" : "VmRSS:";
  while (f >> key) {
    if (key == want) {
      double kib = 0;
      f >> kib;
      return kib * 1024;
    }
    f.ignore(1 << 20, '\n');
  }
  return 0;
}

}  // namespace grains::sim
