#include "sim/state/particle_store.hpp"

#include <cstring>
#include <stdexcept>

namespace grains::sim {

void ParticleStore::configure(FieldSet fields, int wall_history_size) {
  if (size() != 0) throw std::logic_error("ParticleStore::configure after particles were added");
  fields_ = fields;
  wall_history_size_ = fields.has(Field::WallHistory) ? wall_history_size : 0;
}

std::vector<std::string> ParticleStore::field_names() const {
  std::vector<std::string> n{"id", "position", "velocity", "force", "radius", "mass", "material", "shape"};
  if (fields_.has(Field::AngularVelocity)) n.emplace_back("angular_velocity");
  if (fields_.has(Field::Torque)) n.emplace_back("torque");
  if (fields_.has(Field::Inertia)) n.emplace_back("inertia");
  if (fields_.has(Field::Orientation)) n.emplace_back("orientation");
  if (fields_.has(Field::WallHistory))
    n.emplace_back("wall_history[" + std::to_string(wall_history_size_) + "]");
  if (fields_.has(Field::AngularMomentum)) n.emplace_back("angular_momentum");
  if (fields_.has(Field::SemiAxes)) n.emplace_back("semi_axes");
  if (fields_.has(Field::ShapeForm)) n.emplace_back("shape_form");
  if (fields_.has(Field::Body)) {
    n.emplace_back("body");
    n.emplace_back("body_offset");
  }
  return n;
}

std::size_t ParticleStore::add(std::int64_t gid, const Vec3& xi, const Vec3& vi, double r, double m,
                               int mat, int shp) {
  if (n_ghost() != 0) throw std::logic_error("ParticleStore::add with ghosts present");
  id.push_back(gid);
  x.push_back(xi);
  v.push_back(vi);
  f.push_back(Vec3::Zero());
  radius.push_back(r);
  mass.push_back(m);
  inv_mass.push_back(1.0 / m);
  material.push_back(mat);
  shape.push_back(shp);
  if (fields_.has(Field::AngularVelocity)) omega.push_back(Vec3::Zero());
  if (fields_.has(Field::Torque)) torque.push_back(Vec3::Zero());
  if (fields_.has(Field::Inertia)) {
    const double i = 0.4 * m * r * r;  // solid sphere; shapes overwrite
    inertia.push_back(Vec3(i, i, i));
  }
  if (fields_.has(Field::Orientation)) orientation.push_back(Quat::Identity());
  wall_history.resize(wall_history.size() + wall_history_size_, 0.0);
  if (fields_.has(Field::AngularMomentum)) angular_momentum.push_back(Vec3::Zero());
  if (fields_.has(Field::SemiAxes)) semi_axes.push_back(Vec3(r, r, r));
  if (fields_.has(Field::ShapeForm)) form.push_back({r * r, 0, 0, r * r, 0, r * r});
  if (fields_.has(Field::Body)) {
    body.push_back(-1);
    body_offset.push_back(Vec3::Zero());
  }
  return n_owned_++;
}

void ParticleStore::add_ghost(const ParticleStore& from, std::size_t s, const Vec3& shift) {
  id.push_back(from.id[s]);
  x.push_back(from.x[s] + shift);
  v.push_back(from.v[s]);
  f.push_back(Vec3::Zero());
  radius.push_back(from.radius[s]);
  mass.push_back(from.mass[s]);
  inv_mass.push_back(from.inv_mass[s]);
  material.push_back(from.material[s]);
  shape.push_back(from.shape[s]);
  if (fields_.has(Field::AngularVelocity)) omega.push_back(from.omega[s]);
  if (fields_.has(Field::Torque)) torque.push_back(Vec3::Zero());
  if (fields_.has(Field::Inertia)) inertia.push_back(from.inertia[s]);
  if (fields_.has(Field::Orientation)) orientation.push_back(from.orientation[s]);
  wall_history.resize(wall_history.size() + wall_history_size_, 0.0);
  if (fields_.has(Field::AngularMomentum)) angular_momentum.push_back(from.angular_momentum[s]);
  if (fields_.has(Field::SemiAxes)) semi_axes.push_back(from.semi_axes[s]);
  if (fields_.has(Field::ShapeForm)) form.push_back(from.form[s]);
  if (fields_.has(Field::Body)) {
    body.push_back(from.body[s]);
    body_offset.push_back(from.body_offset[s]);
  }
}

void ParticleStore::clear_ghosts() {
  const std::size_t n = n_owned_;
  for_each_field([n](auto& vec, int w) { vec.resize(n * static_cast<std::size_t>(w)); });
}

void ParticleStore::remove_if(const std::vector<char>& remove) {
  clear_ghosts();
  std::vector<std::size_t> keep;
  keep.reserve(n_owned_);
  for (std::size_t i = 0; i < n_owned_; ++i)
    if (!remove[i]) keep.push_back(i);
  permute(keep);
}

void ParticleStore::permute(const std::vector<std::size_t>& order) {
  clear_ghosts();
  for_each_field([&order](auto& vec, int w) {
    using V = std::decay_t<decltype(vec)>;
    V out(order.size() * static_cast<std::size_t>(w));
    for (std::size_t k = 0; k < order.size(); ++k)
      for (int c = 0; c < w; ++c) out[k * w + c] = vec[order[k] * w + c];
    vec.swap(out);
  });
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

void ParticleStore::unpack_owned(const char* rec) {
  if (n_ghost() != 0) throw std::logic_error("ParticleStore::unpack_owned with ghosts present");
  for_each_field([&](auto& vec, int w) {
    const std::size_t bytes = sizeof(vec[0]) * static_cast<std::size_t>(w);
    vec.resize(vec.size() + static_cast<std::size_t>(w));
    std::memcpy(reinterpret_cast<char*>(vec.data() + vec.size() - static_cast<std::size_t>(w)), rec, bytes);
    rec += bytes;
  });
  ++n_owned_;
}

void ParticleStore::unpack_ghost(const char* rec, const Vec3& shift) {
  const std::size_t k = size();
  for_each_field([&](auto& vec, int w) {
    const std::size_t bytes = sizeof(vec[0]) * static_cast<std::size_t>(w);
    vec.resize(vec.size() + static_cast<std::size_t>(w));
    std::memcpy(reinterpret_cast<char*>(vec.data() + vec.size() - static_cast<std::size_t>(w)), rec, bytes);
    rec += bytes;
  });
  x[k] += shift;
  f[k].setZero();
  if (fields_.has(Field::Torque)) torque[k].setZero();
}

std::size_t ParticleStore::kinematic_bytes() const {
  std::size_t b = 2 * sizeof(Vec3);
  if (fields_.has(Field::AngularVelocity)) b += sizeof(Vec3);
  if (fields_.has(Field::Orientation)) b += sizeof(Quat);
  if (fields_.has(Field::ShapeForm)) b += sizeof(std::array<double, 6>);
  return b;
}

namespace {
template <class T>
void put(std::vector<char>& buf, const T& v) {
  const auto* c = reinterpret_cast<const char*>(&v);
  buf.insert(buf.end(), c, c + sizeof(T));
}
template <class T>
const char* get(const char* rec, T& v) {
  std::memcpy(reinterpret_cast<char*>(&v), rec, sizeof(T));
  return rec + sizeof(T);
}
}  // namespace

void ParticleStore::pack_kinematics(std::size_t i, const Vec3& shift, std::vector<char>& buf) const {
  put(buf, Vec3(x[i] + shift));
  put(buf, v[i]);
  if (fields_.has(Field::AngularVelocity)) put(buf, omega[i]);
  if (fields_.has(Field::Orientation)) put(buf, orientation[i]);
  if (fields_.has(Field::ShapeForm)) put(buf, form[i]);
}

std::size_t ParticleStore::unpack_kinematics(std::size_t i, const char* rec) {
  const char* r = rec;
  r = get(r, x[i]);
  r = get(r, v[i]);
  if (fields_.has(Field::AngularVelocity)) r = get(r, omega[i]);
  if (fields_.has(Field::Orientation)) r = get(r, orientation[i]);
  if (fields_.has(Field::ShapeForm)) r = get(r, form[i]);
  return static_cast<std::size_t>(r - rec);
}

}  // namespace grains::sim
