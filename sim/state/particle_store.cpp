#include "sim/state/particle_store.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "sim/state/free_heap.hpp"
#include "sim/state/huge_pages.hpp"

namespace grains::sim {

namespace {

// Room for one more particle of width w. Ghosts and migrating grains arrive
// one at a time; growing by an eighth instead of doubling keeps a field's
// spare room small, and that room is resident when the block comes from
// pages the heap had used before (issue 26: memory per grain). The periodic
// images of a bed are a few per cent of its grains: one growth per build.
template <class V>
void make_room(V& vec, std::size_t w) {
  if (vec.size() + w > vec.capacity()) vec.reserve(vec.size() + std::max(vec.size() / 8, 64 * w));
}

}  // namespace

void ParticleStore::configure(FieldSet fields, int wall_history_size, int wall_tag_size) {
  if (size() != 0) throw std::logic_error("ParticleStore::configure after particles were added");
  fields_ = fields;
  wall_history_size_ = fields.has(Field::WallHistory) ? wall_history_size : 0;
  wall_tag_size_ = fields.has(Field::WallHistory) ? wall_tag_size : 0;
}

std::vector<std::string> ParticleStore::field_names() const {
  std::vector<std::string> n;
  declare_fields([&](const FieldInfo& f, auto, auto) {
    n.emplace_back(f.width > 1 ? std::string(f.name) + "[" + std::to_string(f.width) + "]" : std::string(f.name));
  });
  return n;
}

std::size_t ParticleStore::add(std::int64_t gid, const Vec3& xi, const Vec3& vi, double r, double m,
                               int mat, int shp) {
  if (n_ghost() != 0) throw std::logic_error("ParticleStore::add with ghosts present");
  const NewParticle q{gid, xi, vi, r, m, mat, shp};
  declare_fields([&](const FieldInfo& f, auto member, auto fresh) {
    auto& vec = this->*member;
    for (int c = 0; c < f.width; ++c) vec.push_back(fresh(q));
  });
  return n_owned_++;
}

void ParticleStore::add_ghost(const ParticleStore& from, std::size_t s, const Vec3& shift) {
  const NewParticle none{0, Vec3::Zero(), Vec3::Zero(), 0, 1, 0, 0};
  declare_fields([&](const FieldInfo& f, auto member, auto fresh) {
    auto& vec = this->*member;
    const auto& src = from.*member;
    for (int c = 0; c < f.width; ++c)
      vec.push_back(f.ghost_zero ? fresh(none) : src[s * static_cast<std::size_t>(f.width) + c]);
  });
  x.back() += shift;
}

void ParticleStore::clear_ghosts() {
  const std::size_t n = n_owned_;
  for_each_field([n](auto& vec, int w) { vec.resize(n * static_cast<std::size_t>(w)); });
}

void ParticleStore::keep_ghosts(const std::vector<char>& keep) {
  const std::size_t n = n_owned_, total = size();
  for_each_field([&](auto& vec, int w) {
    const auto ww = static_cast<std::size_t>(w);
    std::size_t m = n;
    for (std::size_t g = n; g < total; ++g)
      if (keep[g - n]) {
        if (m != g)
          for (std::size_t c = 0; c < ww; ++c) vec[m * ww + c] = vec[g * ww + c];
        ++m;
      }
    vec.resize(m * ww);
  });
}

void ParticleStore::remove_if(const std::vector<char>& remove) {
  clear_ghosts();
  // In place, from the first particle removed on: the kept ones move down
  // in their order and every field keeps its block and room. (A migration
  // removes a few grains or none; a permutation into new blocks cost a
  // copy of every field each time, 6 % of a 2-rank pour's neighbour stage:
  // bench/RESULTS.md, 2026-12-08.)
  std::size_t first = 0;
  while (first < n_owned_ && !remove[first]) ++first;
  if (first == n_owned_) return;
  std::size_t kept = first;
  for (std::size_t i = first; i < n_owned_; ++i) kept += !remove[i];
  for_each_field([&](auto& vec, int w) {
    const auto ww = static_cast<std::size_t>(w);
    std::size_t m = first;
    for (std::size_t i = first + 1; i < n_owned_; ++i)
      if (!remove[i]) {
        for (std::size_t c = 0; c < ww; ++c) vec[m * ww + c] = vec[i * ww + c];
        ++m;
      }
    vec.resize(kept * ww);
  });
  n_owned_ = kept;
}

void ParticleStore::permute(const std::vector<std::size_t>& order) {
  clear_ghosts();
  std::size_t most = 0;  // the largest field, in bytes
  for_each_field([&](auto& vec, int w) {
    using T = typename std::decay_t<decltype(vec)>::value_type;
    static_assert(alignof(T) <= alignof(Quat) && std::is_trivially_destructible_v<T>);
    most = std::max(most, order.size() * static_cast<std::size_t>(w) * sizeof(T));
  });
  if (most < kMappedBlockBytes) {
    // Small fields: each into a new block from the heap, which reuses the
    // block the field before gave back (no copy back).
    for_each_field([&order](auto& vec, int w) {
      using V = std::decay_t<decltype(vec)>;
      V out;  // the field's room is kept (after a build, the room its ghosts took)
      out.reserve(std::max(order.size() * static_cast<std::size_t>(w), vec.capacity()));
      out.resize(order.size() * static_cast<std::size_t>(w));
      for (std::size_t k = 0; k < order.size(); ++k)
        for (int c = 0; c < w; ++c) out[k * w + c] = vec[order[k] * w + c];
      vec.swap(out);
    });
  } else {
    // Large fields: each gathered into one scratch block and copied back.
    // The fields keep their blocks (and their room for ghosts), and one block
    // is faulted in per permutation instead of a new one per field.
    std::vector<Quat> scratch;  // aligned for every field's type
    reserve_huge(scratch, (most + sizeof(Quat) - 1) / sizeof(Quat));
    scratch.resize((most + sizeof(Quat) - 1) / sizeof(Quat));  // (Quat's constructor writes nothing)
    for_each_field([&](auto& vec, int w) {
      using T = typename std::decay_t<decltype(vec)>::value_type;
      T* const out = reinterpret_cast<T*>(scratch.data());
      const std::size_t m = order.size() * static_cast<std::size_t>(w);
      for (std::size_t k = 0; k < order.size(); ++k)
        for (int c = 0; c < w; ++c) out[k * w + c] = vec[order[k] * w + c];
      vec.resize(m);
      std::copy(out, out + m, vec.begin());
    });
  }
  n_owned_ = order.size();
}

std::size_t ParticleStore::record_bytes() {
  std::size_t b = 0;
  for_each_field([&b](auto& vec, int w) { b += sizeof(vec[0]) * static_cast<std::size_t>(w); });
  return b;
}

void ParticleStore::pack(std::size_t i, std::vector<char>& buf) {
  for_each_field([&](auto& vec, int w) {
    const std::size_t bytes = sizeof(vec[0]) * static_cast<std::size_t>(w);
    const auto* src = reinterpret_cast<const char*>(vec.data() + i * static_cast<std::size_t>(w));
    buf.insert(buf.end(), src, src + bytes);
  });
}

void ParticleStore::pack_records(const std::vector<std::uint32_t>& idx, std::vector<char>& buf) {
  const std::size_t rec = record_bytes(), base = buf.size();
  buf.resize(base + idx.size() * rec);
  char* const out = buf.data() + base;
  std::size_t off = 0;  // the field's place in a record
  for_each_field([&](auto& vec, int w) {
    const std::size_t ww = static_cast<std::size_t>(w), bytes = sizeof(vec[0]) * ww;
    for (std::size_t k = 0; k < idx.size(); ++k)
      std::memcpy(out + k * rec + off, reinterpret_cast<const char*>(vec.data() + idx[k] * ww), bytes);
    off += bytes;
  });
}

void ParticleStore::unpack_owned(const char* rec) {
  if (n_ghost() != 0) throw std::logic_error("ParticleStore::unpack_owned with ghosts present");
  for_each_field([&](auto& vec, int w) {
    const std::size_t bytes = sizeof(vec[0]) * static_cast<std::size_t>(w);
    make_room(vec, static_cast<std::size_t>(w));
    vec.resize(vec.size() + static_cast<std::size_t>(w));
    std::memcpy(reinterpret_cast<char*>(vec.data() + vec.size() - static_cast<std::size_t>(w)), rec, bytes);
    rec += bytes;
  });
  ++n_owned_;
}

void ParticleStore::reserve_more(std::size_t count) {
  const std::size_t want = size() + count;
  for_each_field([want](auto& vec, int w) {
    const std::size_t m = want * static_cast<std::size_t>(w);
    if (vec.capacity() >= m) return;
    std::decay_t<decltype(vec)> more;
    reserve_huge(more, m);
    more.assign(vec.begin(), vec.end());
    vec.swap(more);
  });
}

void ParticleStore::unpack_ghosts(const char* recs, std::size_t count, const Vec3& shift) {
  if (count == 0) return;
  const std::size_t k0 = size(), rec = record_bytes();
  std::size_t off = 0;
  for_each_field([&](auto& vec, int w) {
    const std::size_t ww = static_cast<std::size_t>(w), bytes = sizeof(vec[0]) * ww;
    if (vec.size() + count * ww > vec.capacity())
      vec.reserve(vec.size() + std::max(count * ww, std::max(vec.size() / 8, 64 * ww)));
    vec.resize(vec.size() + count * ww);
    char* const out = reinterpret_cast<char*>(vec.data() + k0 * ww);
    for (std::size_t k = 0; k < count; ++k) std::memcpy(out + k * bytes, recs + k * rec + off, bytes);
    off += bytes;
  });
  for (std::size_t k = k0; k < k0 + count; ++k) {
    x[k] += shift;
    f[k].setZero();
    if (fields_.has(Field::Torque)) torque[k].setZero();
  }
}

std::size_t ParticleStore::kinematic_bytes() const {
  std::size_t b = 0;
  declare_fields([&](const FieldInfo& f, auto member, auto) {
    if (f.kinematic) b += sizeof((this->*member)[0]) * static_cast<std::size_t>(f.width);
  });
  return b;
}

void ParticleStore::pack_kinematics(const std::vector<std::uint32_t>& idx, std::vector<char>& buf) const {
  buf.resize(idx.size() * kinematic_bytes());
  char* out = buf.data();
  declare_fields([&](const FieldInfo& f, auto member, auto) {
    if (!f.kinematic) return;
    const auto& vec = this->*member;
    using T = typename std::decay_t<decltype(vec)>::value_type;
    const auto w = static_cast<std::size_t>(f.width);
    // The image's position is x + shift, with no shift here: + 0 as the
    // build's record and a local copy give it (-0 becomes +0).
    bool position = false;
    if constexpr (std::is_same_v<T, Vec3>) position = member == &ParticleStore::x;
    for (const auto i : idx)
      for (std::size_t c = 0; c < w; ++c) {
        T v = vec[i * w + c];
        if constexpr (std::is_same_v<T, Vec3>)
          if (position) v += Vec3::Zero();
        std::memcpy(out, &v, sizeof(T));
        out += sizeof(T);
      }
  });
}

void ParticleStore::unpack_kinematics(std::size_t start, std::size_t count, const char* buf) {
  declare_fields([&](const FieldInfo& f, auto member, auto) {
    if (!f.kinematic) return;
    auto& vec = this->*member;
    using T = typename std::decay_t<decltype(vec)>::value_type;
    const auto w = static_cast<std::size_t>(f.width);
    std::memcpy(static_cast<void*>(vec.data() + start * w), buf, sizeof(T) * w * count);
    buf += sizeof(T) * w * count;
  });
}

}  // namespace grains::sim
