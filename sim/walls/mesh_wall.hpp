#pragma once
// The mesh wall kind: a triangle mesh from an STL, OBJ or OFF file (a drum,
// a hopper, a mixer blade), open or closed, two-sided unless the case says
// one-sided, at rest or moving: a translation (constant velocity, a
// sinusoidal vibration) and a rotation about an axis, combined, from a start
// time and over a linear ramp. Registered in wall_kinds.hpp; the interface is
// described in wall_kind.hpp.
//
// The mesh never moves in memory: it is kept in its body frame (as loaded,
// after the case's scale, rotation and translation) with its topology and
// bounding-volume hierarchy (contact/mesh/mesh_surface.hpp), and particles are
// brought into that frame. The pose is a function of the wall's motion clock
// only, so a restart continues bitwise from the checkpointed clock. A change
// of motion on the way (a script's stage, a restart with an edited case)
// rebases it: the pose at that time is kept and the new motion runs from it.
//
// Contacts: one per physical contact (face, edge or vertex; the rule is in
// mesh_surface.hpp). Each keeps its history in one of the wall's slots of
// the particle's wall history, found again the next step by its normal (the
// slot's tag: the contact of the previous step whose normal is nearest,
// within 60 degrees), so the tangential spring follows a particle from one
// triangle to its neighbour. Not a slot per triangle: `contacts_per_particle`
// slots (default 4) per particle and mesh wall, with a mask of those in use;
// a contact beyond them has no history.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "contact/ellipsoid/ellipsoid.hpp"
#include "contact/mesh/mesh_surface.hpp"
#include "sim/keys/effect_doc.hpp"
#include "sim/state/particle_store.hpp"
#include "sim/walls/wall_kind.hpp"

namespace grains::sim {

struct MeshWall : WallCommon {
  static constexpr const char* kind = "mesh";
  static constexpr const char* position_name = "offset";
  static constexpr bool controllable = true;  // walls[].control (wall_control.hpp)
  static constexpr bool near_items = true;  // each listed particle's near triangles
  static constexpr bool tagged = true;  // slots carry the contact's normal, and a mask of those held (ParticleStore::wall_tags)
  static constexpr int kMaxFound = 16;  // contacts looked at per particle and step

  std::shared_ptr<const contact::MeshSurface> surface;  // body frame
  std::string file;
  // Motion (world frame, from the pose at load).
  Vec3 axis{0, 0, 1};           // unit rotation axis
  Vec3 axis_point{0, 0, 0};     // a point on it at motion time 0
  double angular_velocity = 0;  // rad/s, right-handed about axis
  Vec3 vibration_amplitude{0, 0, 0};
  double vibration_frequency = 0;  // Hz
  double start = 0, ramp = 0;      // s
  Vec3 torque_point{0, 0, 0};      // moves with the wall
  int contacts_per_particle = 4;
  double reach = 0;  // largest distance of a vertex from the axis (bounds the surface speed)

  // A change of motion at motion time base_time (rebase()): the translation
  // and the angle then, and the new vibration's displacement then (taken off,
  // so that the pose is continuous). Unused until the first change, so that
  // the motion of a case is computed as it always was.
  bool rebased = false;
  double base_time = 0, base_angle = 0;
  Vec3 base_offset{0, 0, 0}, base_vibration{0, 0, 0};

  // Pose at the motion clock: world = R body + T.
  double motion_time = 0;
  Vec3 offset{0, 0, 0};  // translation since motion time 0 (position())
  double angle = 0;      // rotation about axis since motion time 0
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Vec3 T{0, 0, 0};
  Vec3 v_now{0, 0, 0}, w_now{0, 0, 0};
  bool moving = false;

  static std::string summary() {
    return "A triangle mesh from an STL (ASCII or binary), OBJ or OFF file: a drum, a hopper, a mixer. Open meshes "
           "are fine; two-sided unless one_sided. One contact per physical contact with a face, an edge or a vertex, "
           "its tangential history carried from triangle to triangle. Moves by a translation (velocity, a "
           "sinusoidal vibration) and a rotation about an axis, combined, from `start` over a linear `ramp`; the "
           "surface velocity enters the contact law. Force and torque on it are in output.wall_loads.";
  }
  static std::vector<KeySpec> keys() {
    const double inf = std::numeric_limits<double>::infinity();
    using K = KeyType;
    return {key("file", K::String, "mesh file: .stl (ASCII or binary), .obj or .off, relative to the case file").req(),
            key("scale", K::Number, "factor applied to the file's coordinates first (0.001: a file in mm)")
                .def(1.0)
                .in(0, inf, true),
            key("rotate_axis", K::Vec3, "axis of a rotation applied on load, after scale").def("[0, 0, 1]"),
            key("rotate_angle", K::Number, "angle of that rotation, degrees").def(0.0).si("deg"),
            key("translate", K::Vec3, "translation applied on load, last").def("[0, 0, 0]").si("m"),
            key("one_sided", K::Bool,
                "true: faces push only towards their counter-clockwise (front) side, as the file winds them")
                .def_bool(false),
            key("axis", K::Vec3, "rotation axis of the motion (normalised for you)").def("[0, 0, 1]"),
            key("axis_point", K::Vec3, "a point on the rotation axis").def("the mesh's bounding-box centre").si("m"),
            key("angular_velocity", K::Number, "rotation speed about axis, right-handed (rad/s)").def(0.0).si("rad/s"),
            key("rpm", K::Number, "rotation speed in revolutions per minute (instead of angular_velocity)")
                .def(0.0),
            key("vibration_amplitude", K::Vec3, "displacement amplitude of a sinusoidal vibration")
                .def("[0, 0, 0]")
                .si("m"),
            key("vibration_frequency", K::Number, "frequency of that vibration").def(0.0).si("Hz").in(0, inf),
            key("start", K::Number, "time the motion starts (at rest before: a drum filling)").def(0.0).si("s").in(0, inf),
            key("ramp", K::Number, "time over which the motion's speed rises linearly to full").def(0.0).si("s").in(0, inf),
            key("torque_point", K::Vec3, "point the wall's torque is taken about (moves with the wall)")
                .def("axis_point")
                .si("m"),
            key("contacts_per_particle", K::Integer,
                "contacts a particle can have with this wall at once that keep tangential history")
                .def(4.0)
                .in(1, 16)};
  }

  static MeshWall from_keys(KeyReader& r);

  int slots(bool) const { return contacts_per_particle; }

  /// Set-up errors against the domain [lo, hi] and the initial particles
  /// (empty: none): a mesh 100 times the domain's size (its file in other
  /// units), a mesh outside the domain, a particle starting inside the mesh
  /// beyond `tolerance` of its radius.
  std::string setup_error(const Vec3& lo, const Vec3& hi, const ParticleStore& p, double tolerance) const;
  /// One line for `grains check`: file, triangles, open and non-manifold
  /// edges, sides, memory on every rank, motion.
  std::string description() const;

  // ---- motion ----
  /// Speed factor of the ramp at motion time t, and its integral from 0.
  double ramp_factor(double t) const {
    const double u = t - start;
    if (u <= 0) return 0;
    return ramp > 0 && u < ramp ? u / ramp : 1;
  }
  double ramp_integral(double t) const {
    const double u = t - start;
    if (u <= 0) return 0;
    if (ramp > 0 && u < ramp) return 0.5 * u * u / ramp;
    return u - 0.5 * ramp;
  }
  /// The pose and velocities at motion time t.
  void place(double t) {
    motion_time = t;
    moving = velocity.squaredNorm() > 0 || angular_velocity != 0 ||
             (vibration_frequency > 0 && vibration_amplitude.squaredNorm() > 0) || control.active();
    const double s = ramp_factor(t), integral = rebased ? ramp_integral(t) - ramp_integral(base_time) : ramp_integral(t);
    const double ds = ramp > 0 && t - start > 0 && t - start < ramp ? 1 / ramp : 0;
    offset = velocity * integral;
    if (rebased) offset += base_offset;
    v_now = velocity * s;
    if (vibration_frequency > 0) {
      const double om = 2 * M_PI * vibration_frequency, u = std::max(0.0, t - start);
      offset += vibration_at(t);
      if (rebased) offset -= base_vibration;
      v_now += vibration_amplitude * (ds * std::sin(om * u) + s * om * std::cos(om * u));
    }
    if (control.active()) {  // the controlled translation, on top of the prescribed motion
      offset += control.travel * control.direction;
      v_now += control.speed * control.direction;
    }
    angle = angular_velocity * integral;
    if (rebased) angle += base_angle;
    R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    T = axis_point - R * axis_point + offset;
    w_now = axis * (angular_velocity * s);
  }
  void advance(double dt) { place(motion_time + dt); }
  /// The vibration's displacement at motion time t.
  Vec3 vibration_at(double t) const {
    if (vibration_frequency <= 0) return Vec3::Zero();
    const double om = 2 * M_PI * vibration_frequency, u = std::max(0.0, t - start);
    return vibration_amplitude * (ramp_factor(t) * std::sin(om * u));
  }
  /// Continues from motion time t with the motion the members now give
  /// (velocity, angular_velocity, vibration, start, ramp; not the axis),
  /// from the translation `offset_then` and the angle `angle_then` the wall
  /// had at t: the pose does not jump, its velocity does.
  void rebase(double t, const Vec3& offset_then, double angle_then) {
    rebased = true;
    base_time = t, base_offset = offset_then, base_angle = angle_then;
    base_vibration = vibration_at(t);
    place(t);
  }
  void translate(const Vec3& d) { T += d, offset += d, moving = true; }
  Vec3& position() { return offset; }
  const Vec3& position() const { return offset; }
  /// A bound on how far any point of the surface moved in the last
  /// `elapsed` of its motion clock (the neighbour list's trigger): the
  /// motion's speed integrated over that window, zero before its start.
  double max_displacement(double elapsed) const {
    const double t0 = motion_time - elapsed;
    const double ramped = ramp_integral(motion_time) - ramp_integral(t0);  // <= elapsed
    double d = (velocity.norm() + std::abs(angular_velocity) * reach) * ramped;
    if (vibration_frequency > 0 && motion_time > start)
      d += std::min(2.0, (2 * M_PI * vibration_frequency + (ramp > 0 ? 1 / ramp : 0)) * elapsed) *
           vibration_amplitude.norm();
    return d;
  }
  double max_speed() const {
    const double vib = vibration_amplitude.norm() * (2 * M_PI * vibration_frequency + (ramp > 0 ? 1 / ramp : 0));
    return velocity.norm() + vib + std::abs(angular_velocity) * reach;
  }
  /// The velocity of the wall's surface at world point q.
  Vec3 surface_velocity(const Vec3& q) const {
    return moving ? Vec3(v_now + w_now.cross(q - (axis_point + offset))) : v_now;
  }
  /// The point torques are taken about, now.
  Vec3 load_point() const { return R * torque_point + T; }
  Vec3 to_body(const Vec3& x) const { return moving ? Vec3(R.transpose() * (x - T)) : x; }

  // ---- contacts ----
  /// Particles within their bounding radius + skin of a triangle, and those
  /// triangles (items, one range per listed particle).
  void near_list(const ParticleStore& p, std::size_t n, double skin, bool shapes, std::vector<std::uint32_t>& out,
                 NearItems& items) const;

  template <bool Shapes, class Slots, class Emit>
  GRAINS_INLINE void contacts(const ParticleStore& p, std::size_t i, std::span<const std::uint32_t> tris,
                              Slots&& slots, Emit&& emit) const {
    contact::MeshContact found[kMaxFound];
    int n = 0;
    if constexpr (Shapes) {
      if (p.shape[i] == kEllipsoid) {
        n = ellipsoid_contacts(p, i, tris, found);
        if (n > 0) emit_all(found, n, slots, emit);
        return;
      }
    }
    // Spheres: the common case, one triangle whose face the centre is over,
    // straight to the contact (what sphere_contacts computes for it).
    // The centre in the mesh's frame: p.x[i] itself at rest (no copy).
    Vec3 moved;
    const Vec3& x = moving ? (moved = to_body(p.x[i])) : p.x[i];
    const double r = slots.grown(p.radius[i]);
    const int t = surface->sphere_screen(x, r, tris);
    if (t == contact::MeshSurface::kNone) return;
    if (t >= 0) {
      Vec3 nb;
      double s;
      surface->face_normal(x, t, nb, s);
      if (!contact::MeshSurface::face_touches(s, r)) return;
      contact::ContactGeometry g;
      g.normal = moving ? Vec3(R * nb) : nb;
      g.point = moving ? Vec3(R * Vec3(x - nb * s) + T) : Vec3(x - nb * s);
      g.overlap = r - s;
      g.radius = r;
      emit_one(g, slots, emit);
      return;
    }
    n = std::min(surface->resolve_sphere(x, r, tris, found, kMaxFound), kMaxFound);
    if (n > 0) emit_all(found, n, slots, emit);
  }

  bool touches(const Vec3& x, double r) const { return surface->distance(to_body(x), r) < r; }
  bool touches(const contact::Ellipsoid& e) const;
  /// Depth of the deepest contact of an ellipsoid (0 when clear).
  double ellipsoid_depth(const contact::Ellipsoid& e) const;
  /// Largest depth by which a sphere overlaps the surface (0 when clear).
  double overlap(const Vec3& x, double r) const { return std::max(0.0, r - surface->distance(to_body(x), r)); }

  /// Its triangles as they are now.
  void cells(WallSurface& s, const Vec3&, double) const {
    const int first = static_cast<int>(s.points.size());
    for (const auto& v : surface->vertices()) s.points.push_back(R * v + T);
    for (const auto& f : surface->faces()) s.triangles.push_back({first + f[0], first + f[1], first + f[2]});
  }

  /// The motion clock and the pose (T, then R by rows), for the record; the
  /// triangles are the wall's cells in the same file, already posed.
  std::vector<double> record() const {
    return {motion_time, T.x(), T.y(), T.z(), R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2),
            surface->one_sided() ? 1.0 : 0.0};
  }
  /// The wall as `grains analyze` sees it: its posed triangles, at rest.
  static bool from_record(const std::vector<double>& v, const WallSurface& cells, MeshWall& w);


 private:
  int ellipsoid_contacts(const ParticleStore& p, std::size_t i, std::span<const std::uint32_t> tris,
                         contact::MeshContact* out) const;

  // The slot of a contact with this normal: among the held slots not yet
  // taken this step, the one whose contact's normal is nearest (within 60
  // degrees), else the first free slot (added to held), else -1 (no
  // history). Its tag takes the normal.
  template <class Slots>
  GRAINS_INLINE int take_slot(const Vec3& normal, const Slots& slots, unsigned& held, unsigned taken) const {
    int slot = -1;
    const unsigned cand = held & ~taken;
    auto cosine = [&](int k) { return Eigen::Map<const Vec3>(slots.tag(k)).dot(normal); };
    if (cand == 1u) {  // the usual case: slot 0 alone
      if (cosine(0) > 0.5) slot = 0;
    } else if (cand != 0 && (cand & (cand - 1)) == 0) {  // another alone
      const int k = __builtin_ctz(cand);
      if (cosine(k) > 0.5) slot = k;
    } else {
      double best = 0.5;
      for (unsigned m = cand; m != 0; m &= m - 1) {
        const int k = __builtin_ctz(m);
        const double c = cosine(k);
        if (c > best) best = c, slot = k;
      }
    }
    if (slot < 0) {
      const unsigned free = ((1u << contacts_per_particle) - 1u) & ~(held | taken);
      if (free == 0) return -1;
      slot = __builtin_ctz(free);
      held |= 1u << slot;
    }
    double* t = slots.tag(slot);
    t[0] = normal.x(), t[1] = normal.y(), t[2] = normal.z();
    return slot;
  }

  // One contact (the common case: no contact array).
  template <class Slots, class Emit>
  GRAINS_INLINE void emit_one(const contact::ContactGeometry& g, Slots& slots, Emit& emit) const {
    int slot = -1;
    if constexpr (std::decay_t<Slots>::keeps_history()) {
      unsigned held = slots.mask();
      const unsigned before = held;
      slot = take_slot(g.normal, slots, held, 0u);
      if (held != before) slots.set_mask(held);
    }
    emit(g, slot);
  }

  template <class Slots, class Emit>
  GRAINS_INLINE void emit_all(const contact::MeshContact* found, int n, Slots& slots, Emit& emit) const {
    unsigned taken = 0;
    unsigned held = 0;  // the slots holding a contact (the mask before the tags)
    if constexpr (std::decay_t<Slots>::keeps_history()) held = slots.mask();
    const unsigned held_before = held;
    for (int j = 0; j < n; ++j) {
      contact::ContactGeometry g;
      g.normal = moving ? Vec3(R * found[j].normal) : found[j].normal;
      g.point = moving ? Vec3(R * found[j].point + T) : found[j].point;
      g.overlap = found[j].depth;
      g.radius = found[j].radius;
      int slot = -1;
      if constexpr (std::decay_t<Slots>::keeps_history()) {
        slot = take_slot(g.normal, slots, held, taken);
        if (slot >= 0) taken |= 1u << slot;
      }
      emit(g, slot);
    }
    if constexpr (std::decay_t<Slots>::keeps_history())
      if (held != held_before) slots.set_mask(held);
  }
};

}  // namespace grains::sim
