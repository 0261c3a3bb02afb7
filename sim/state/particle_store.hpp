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
  /// wall_tag_size: doubles per particle tagging the slots of walls that
  /// find their contacts again by a tag (mesh walls: each contact's normal).
  void configure(FieldSet fields, int wall_history_size, int wall_tag_size = 0);

  FieldSet fields() const { return fields_; }
  int wall_history_size() const { return wall_history_size_; }
  int wall_tag_size() const { return wall_tag_size_; }
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
  /// Keeps the ghosts g with keep[g - n_owned()] set, in their order.
  void keep_ghosts(const std::vector<char>& keep);
  /// Room in every field for `count` more particles (ghosts about to
  /// arrive), so that they do not grow each field several times.
  void reserve_more(std::size_t count);
  /// Particles the fields have room for.
  std::size_t room() const { return id.capacity(); }
  /// Remove owned particles whose flag is set (order of the rest is kept).
  void remove_if(const std::vector<char>& remove);
  /// Reorder owned particles: new index k takes old index order[k].
  void permute(const std::vector<std::size_t>& order);

  // ---- byte records (MPI migration and ghosts) ----
  /// Bytes of one particle's record holding every allocated field.
  std::size_t record_bytes();
  /// Appends the full record of particle i to buf.
  void pack(std::size_t i, std::vector<char>& buf);
  /// Appends the full records of particles idx[0], idx[1], ... to buf (what
  /// pack() writes for each, written field by field).
  void pack_records(const std::vector<std::uint32_t>& idx, std::vector<char>& buf);
  /// Appends an owned particle from a record (no ghosts may be present).
  void unpack_owned(const char* rec);
  /// Appends `count` ghosts from consecutive records, their positions
  /// shifted by `shift`, their force and torque zero.
  void unpack_ghosts(const char* recs, std::size_t count, const Vec3& shift);
  /// The fields that change every step (position, velocity and, when they
  /// exist, angular velocity, orientation and shape form): what a ghost
  /// update sends.
  std::size_t kinematic_bytes() const;
  /// The kinematic fields of particles idx[0], idx[1], ... into buf (sized
  /// here to idx.size() * kinematic_bytes()), field by field: each field's
  /// values for all of them, then the next field's.
  void pack_kinematics(const std::vector<std::uint32_t>& idx, std::vector<char>& buf) const;
  /// Overwrites the kinematic fields of particles start .. start + count - 1
  /// from what pack_kinematics wrote for count particles.
  void unpack_kinematics(std::size_t start, std::size_t count, const char* buf);

  // ---- core fields ----
  std::vector<std::int64_t> id;
  std::vector<Vec3> x, v, f;
  std::vector<double> radius, mass, inv_mass;
  std::vector<std::int32_t> material, shape;
  // ---- optional fields (empty unless declared) ----
  std::vector<Vec3> omega, torque, inertia;
  std::vector<Quat> orientation;
  std::vector<double> wall_history;  // size() * wall_history_size()
  std::vector<double> wall_tags;     // size() * wall_tag_size()
  std::vector<Vec3> angular_momentum, semi_axes;
  std::vector<std::array<double, 6>> form;
  std::vector<std::int64_t> body;  // id of the clump this ball belongs to, -1 for a free particle
  std::vector<Vec3> body_offset;   // ball centre - body centre of mass, in the body frame

  /// Applies fn(name, unit, vector&, width) to every allocated per-particle
  /// array, core first; width is the number of entries per particle (the
  /// fields of declare_fields, for checkpoints).
  template <class Fn>
  void visit_fields(Fn&& fn) {
    declare_fields([&](const FieldInfo& f, auto member, auto) { fn(f.name, f.unit, this->*member, f.width); });
  }

  /// What the one list of fields says of each field.
  struct FieldInfo {
    const char* name;
    const char* unit;
    int width = 1;           // entries per particle
    bool kinematic = false;  // changes every step: sent in each ghost update (pack_kinematics)
    bool ghost_zero = false; // a ghost starts from zero (an accumulator, history), not from its owner's value
    // A checkpoint of a stage without this field's effect (frictionless
    // spheres: no rotation, no wall history) may lack it; a restart with the
    // effect then starts it as a new particle's, the exact state of such
    // spheres (io/checkpoint, docs/checkpoint.md).
    bool restart_fresh = false;
  };
  /// The arguments of add(): what a new particle's fields are made from.
  struct NewParticle {
    std::int64_t id;
    Vec3 x, v;
    double r, m;
    int material, shape;
  };

  /// The one list of per-particle fields: fn(info, member pointer, fresh)
  /// for every field that exists, core first, where fresh(NewParticle) is a
  /// new particle's value. field_names, add, add_ghost, permute, the MPI
  /// records and ghost updates, and checkpoints all go through it, so a new
  /// field added here is carried everywhere (docs/architecture.md).
  template <class Fn>
  void declare_fields(Fn&& fn) const {
    using P = ParticleStore;
    using Q = const NewParticle&;
    auto zero3 = [](Q) { return Vec3(Vec3::Zero()); };
    fn(FieldInfo{"id", ""}, &P::id, [](Q q) { return q.id; });
    fn(FieldInfo{"position", "m", 1, true}, &P::x, [](Q q) { return q.x; });
    fn(FieldInfo{"velocity", "m/s", 1, true}, &P::v, [](Q q) { return q.v; });
    fn(FieldInfo{"force", "N", 1, false, true}, &P::f, zero3);
    fn(FieldInfo{"radius", "m"}, &P::radius, [](Q q) { return q.r; });
    fn(FieldInfo{"mass", "kg"}, &P::mass, [](Q q) { return q.m; });
    fn(FieldInfo{"inv_mass", "1/kg"}, &P::inv_mass, [](Q q) { return 1.0 / q.m; });
    fn(FieldInfo{"material", ""}, &P::material, [](Q q) { return std::int32_t(q.material); });
    fn(FieldInfo{"shape", ""}, &P::shape, [](Q q) { return std::int32_t(q.shape); });
    if (fields_.has(Field::AngularVelocity)) fn(FieldInfo{"angular_velocity", "rad/s", 1, true, false, true}, &P::omega, zero3);
    if (fields_.has(Field::Torque)) fn(FieldInfo{"torque", "N m", 1, false, true, true}, &P::torque, zero3);
    if (fields_.has(Field::Inertia))  // a solid sphere; shapes overwrite
      fn(FieldInfo{"inertia", "kg m^2", 1, false, false, true}, &P::inertia, [](Q q) {
        const double i = 0.4 * q.m * q.r * q.r;
        return Vec3(i, i, i);
      });
    if (fields_.has(Field::Orientation))
      fn(FieldInfo{"orientation", "", 1, true}, &P::orientation, [](Q) { return Quat(Quat::Identity()); });
    if (wall_history_size_ > 0)
      fn(FieldInfo{"wall_history", "m (tangential), N m (rolling)", wall_history_size_, false, true, true}, &P::wall_history,
         [](Q) { return 0.0; });
    if (wall_tag_size_ > 0)
      fn(FieldInfo{"wall_contact_normal", "", wall_tag_size_, false, true, true}, &P::wall_tags, [](Q) { return 0.0; });
    if (fields_.has(Field::AngularMomentum)) fn(FieldInfo{"angular_momentum", "kg m^2/s"}, &P::angular_momentum, zero3);
    if (fields_.has(Field::SemiAxes)) fn(FieldInfo{"semi_axes", "m"}, &P::semi_axes, [](Q q) { return Vec3(q.r, q.r, q.r); });
    if (fields_.has(Field::ShapeForm))
      fn(FieldInfo{"shape_form", "m^2", 1, true}, &P::form,
         [](Q q) { return std::array<double, 6>{q.r * q.r, 0, 0, q.r * q.r, 0, q.r * q.r}; });
    if (fields_.has(Field::Body)) {
      fn(FieldInfo{"body", ""}, &P::body, [](Q) { return std::int64_t{-1}; });
      fn(FieldInfo{"body_offset", "m"}, &P::body_offset, zero3);
    }
  }

 private:
  template <class Fn>
  void for_each_field(Fn&& fn) {
    declare_fields([&](const FieldInfo& f, auto member, auto) { fn(this->*member, f.width); });
  }
  FieldSet fields_{};
  int wall_history_size_ = 0;
  int wall_tag_size_ = 0;
  std::size_t n_owned_ = 0;
};

}  // namespace grains::sim
