#pragma once
// ParticleStore: the particles of one rank as a structure of arrays.
//
// Layout decisions (they carry every later feature):
//  * Indices [0, n_owned) are the particles this rank integrates; indices
//    [n_owned, size) are ghosts (copies of particles owned elsewhere: another
//    MPI rank or a periodic image). Ghosts carry kinematics and shape but
//    are never integrated.
//  * Every particle has a global id that never changes; contact history is
//    keyed by ids, not by local indices, so it survives re-sorting and can
//    travel with its particle to another rank.
//  * Core fields always exist. Optional fields exist only when an effect of
//    the scene declares them (FieldSet): a scene of frictionless spheres
//    allocates no angular velocity, torque, inertia or orientation at all.
//  * Per-particle wall history (one slot group per wall that keeps history)
//    is a per-particle field, so it moves and permutes with its particle.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace grains::sim {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

/// Optional per-particle fields. Core fields (id, position, velocity, force,
/// radius, mass, material, shape) are not listed: they always exist.
enum class Field : std::uint32_t {
  AngularVelocity = 1u << 0,  // omega, world frame
  Torque = 1u << 1,           // world frame
  Inertia = 1u << 2,          // principal moments (body frame); spheres use x only
  Orientation = 1u << 3,      // unit quaternion body -> world
  WallHistory = 1u << 4,      // history slots for particle-wall contacts
  AngularMomentum = 1u << 5,  // world frame; integrated for non-spherical bodies
  SemiAxes = 1u << 6,         // ellipsoid semi-axes (body frame); spheres: (r, r, r)
  ShapeForm = 1u << 7,        // PW85 form Q = R diag(a^2) R^T, packed upper triangle, kept in step
  Body = 1u << 8,             // clump membership: body id (-1: free particle) and body-frame offset
};

/// Shape kinds stored in ParticleStore::shape.
enum ShapeKind : std::int32_t { kSphere = 0, kEllipsoid = 1 };

class FieldSet {
 public:
  constexpr FieldSet() = default;
  constexpr FieldSet(Field f) : bits_(static_cast<std::uint32_t>(f)) {}
  constexpr FieldSet operator|(FieldSet o) const { return FieldSet(bits_ | o.bits_); }
  constexpr FieldSet& operator|=(FieldSet o) { bits_ |= o.bits_; return *this; }
  constexpr bool has(Field f) const { return (bits_ & static_cast<std::uint32_t>(f)) != 0; }
  constexpr bool operator==(const FieldSet&) const = default;

 private:
  constexpr explicit FieldSet(std::uint32_t b) : bits_(b) {}
  std::uint32_t bits_ = 0;
};

class ParticleStore {
 public:
  /// Declare the optional fields before adding particles. wall_history_size is
  /// the number of doubles of history kept per particle for all walls together.
  void configure(FieldSet fields, int wall_history_size);

  FieldSet fields() const { return fields_; }
  int wall_history_size() const { return wall_history_size_; }
  /// Names of the fields that exist, core first (for `grains check`).
  std::vector<std::string> field_names() const;

  std::size_t size() const { return id.size(); }
  std::size_t n_owned() const { return n_owned_; }
  std::size_t n_ghost() const { return size() - n_owned_; }

  /// Append an owned particle (ghosts must be dropped first). Returns its index.
  std::size_t add(std::int64_t gid, const Vec3& x, const Vec3& v, double r, double m,
                  int material, int shape = 0);
  /// Append a ghost copy of particle `src` of `from` shifted by `shift`.
  void add_ghost(const ParticleStore& from, std::size_t src, const Vec3& shift);
  void clear_ghosts();
  /// Remove owned particles whose flag is set (order of the rest is kept).
  void remove_if(const std::vector<char>& remove);
  /// Reorder owned particles: new index k takes old index order[k].
  void permute(const std::vector<std::size_t>& order);

  // ---- byte records (MPI migration and ghosts) ----
  /// Bytes of one particle's record holding every allocated field.
  std::size_t record_bytes();
  /// Appends the full record of particle i to buf.
  void pack(std::size_t i, std::vector<char>& buf);
  /// Appends an owned particle from a record (no ghosts may be present).
  void unpack_owned(const char* rec);
  /// Appends a ghost from a record, its position shifted by `shift`.
  void unpack_ghost(const char* rec, const Vec3& shift);
  /// The fields that change every step (position, velocity and, when they
  /// exist, angular velocity, orientation and shape form): what a ghost
  /// update sends.
  std::size_t kinematic_bytes() const;
  void pack_kinematics(std::size_t i, const Vec3& shift, std::vector<char>& buf) const;
  /// Overwrites the kinematic fields of particle i from a record; returns the bytes read.
  std::size_t unpack_kinematics(std::size_t i, const char* rec);

  // ---- core fields ----
  std::vector<std::int64_t> id;
  std::vector<Vec3> x, v, f;
  std::vector<double> radius, mass, inv_mass;
  std::vector<std::int32_t> material, shape;
  // ---- optional fields (empty unless declared) ----
  std::vector<Vec3> omega, torque, inertia;
  std::vector<Quat> orientation;
  std::vector<double> wall_history;  // size() * wall_history_size()
  std::vector<Vec3> angular_momentum, semi_axes;
  std::vector<std::array<double, 6>> form;
  std::vector<std::int64_t> body;  // id of the clump this ball belongs to, -1 for a free particle
  std::vector<Vec3> body_offset;   // ball centre - body centre of mass, in the body frame

  /// Applies fn(name, unit, vector&, width) to every allocated per-particle
  /// array, core first; width is the number of entries per particle. This is
  /// the one list of fields: permute, ghosts and checkpoints all go through
  /// it, so a new field added here is carried everywhere.
  template <class Fn>
  void visit_fields(Fn&& fn) {
    fn("id", "", id, 1); fn("position", "m", x, 1); fn("velocity", "m/s", v, 1); fn("force", "N", f, 1);
    fn("radius", "m", radius, 1); fn("mass", "kg", mass, 1); fn("inv_mass", "1/kg", inv_mass, 1);
    fn("material", "", material, 1); fn("shape", "", shape, 1);
    if (fields_.has(Field::AngularVelocity)) fn("angular_velocity", "rad/s", omega, 1);
    if (fields_.has(Field::Torque)) fn("torque", "N m", torque, 1);
    if (fields_.has(Field::Inertia)) fn("inertia", "kg m^2", inertia, 1);
    if (fields_.has(Field::Orientation)) fn("orientation", "", orientation, 1);
    if (wall_history_size_ > 0) fn("wall_history", "m (tangential), N m (rolling)", wall_history, wall_history_size_);
    if (fields_.has(Field::AngularMomentum)) fn("angular_momentum", "kg m^2/s", angular_momentum, 1);
    if (fields_.has(Field::SemiAxes)) fn("semi_axes", "m", semi_axes, 1);
    if (fields_.has(Field::ShapeForm)) fn("shape_form", "m^2", form, 1);
    if (fields_.has(Field::Body)) {
      fn("body", "", body, 1);
      fn("body_offset", "m", body_offset, 1);
    }
  }

 private:
  template <class Fn>
  void for_each_field(Fn&& fn) {
    visit_fields([&fn](const char*, const char*, auto& vec, int w) { fn(vec, w); });
  }
  FieldSet fields_{};
  int wall_history_size_ = 0;
  std::size_t n_owned_ = 0;
};

}  // namespace grains::sim
