#include "sim/state/particle_store.hpp"

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

}  // namespace grains::sim
