#include "sim/walls/mesh_wall.hpp"

#include <sstream>

#include "contact/ellipsoid/ellipsoid_mesh.hpp"

namespace grains::sim {

MeshWall MeshWall::from_keys(KeyReader& r) {
  MeshWall w;
  w.file = r.string("file", "");
  const double scale = r.number("scale", 1);
  const Vec3 rot_axis = r.direction("rotate_axis", Vec3(0, 0, 1));
  const double rot_angle = r.number("rotate_angle", 0) * M_PI / 180;
  const Vec3 shift = r.vec3("translate", Vec3::Zero());
  const bool one_sided = r.boolean("one_sided", false);
  w.axis = r.direction("axis", Vec3(0, 0, 1));
  w.angular_velocity = r.number("angular_velocity", 0);
  if (r.has("rpm")) {
    if (r.has("angular_velocity")) r.error("rpm", "give either angular_velocity (rad/s) or rpm, not both");
    w.angular_velocity = r.number("rpm", 0) * 2 * M_PI / 60;
  }
  w.vibration_amplitude = r.vec3("vibration_amplitude", Vec3::Zero());
  w.vibration_frequency = r.number("vibration_frequency", 0);
  if (w.vibration_amplitude.squaredNorm() > 0 && !(w.vibration_frequency > 0))
    r.error("vibration_amplitude", "a vibration needs vibration_frequency > 0");
  w.start = r.number("start", 0);
  w.ramp = r.number("ramp", 0);
  w.contacts_per_particle = static_cast<int>(r.number("contacts_per_particle", 4));

  const auto mesh = r.surface_mesh("file");
  if (!mesh) {
    w.surface = std::make_shared<contact::MeshSurface>();
    return w;
  }
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(rot_angle, rot_axis).toRotationMatrix();
  std::vector<Vec3> v;
  v.reserve(mesh->vertices.size());
  for (const auto& p : mesh->vertices) v.push_back(rot * (scale * p) + shift);
  w.surface = std::make_shared<contact::MeshSurface>(std::move(v), mesh->faces, one_sided);
  const Vec3 centre = 0.5 * (w.surface->bbox_min() + w.surface->bbox_max());
  w.axis_point = r.vec3("axis_point", centre);
  w.torque_point = r.vec3("torque_point", w.axis_point);
  for (const auto& p : w.surface->vertices()) {
    const Vec3 d = p - w.axis_point;
    w.reach = std::max(w.reach, (d - w.axis * w.axis.dot(d)).norm());
  }
  return w;
}

std::string MeshWall::setup_error(const Vec3& dlo, const Vec3& dhi, const ParticleStore& p, double tolerance) const {
  const std::string at = (where.empty() ? "walls" : where) + ": mesh wall '" + name + "' ('" + file + "')";
  const Vec3 lo = surface->bbox_min(), hi = surface->bbox_max();
  const double size = (hi - lo).norm(), diag = (dhi - dlo).norm();
  std::ostringstream e;
  e.precision(4);
  if (size > 100 * diag) {
    e << at << " is " << size / diag << " times the domain's size (bounding-box diagonal " << size << " m against "
      << diag << " m): its file is probably in other units; give scale: 0.001 for a file in millimetres";
    return e.str();
  }
  if ((lo.array() > dhi.array()).any() || (hi.array() < dlo.array()).any()) {
    e << at << " lies outside the domain (its bounding box [" << lo.transpose() << "] to [" << hi.transpose()
      << "], the domain's [" << dlo.transpose() << "] to [" << dhi.transpose() << "]): check translate and scale";
    return e.str();
  }
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    const double depth = p.shape[i] == kEllipsoid ? ellipsoid_depth({p.x[i], p.semi_axes[i], p.orientation[i]})
                                                  : overlap(p.x[i], p.radius[i]);
    if (depth > tolerance * p.radius[i]) {
      e << at << ": particle " << p.id[i] << " at [" << p.x[i].transpose() << "] (radius " << p.radius[i]
        << " m) starts " << depth << " m inside the mesh, " << 100 * depth / p.radius[i]
        << "% of its radius (neighbor.overlap_tolerance accepts " << 100 * tolerance
        << "%): place the particles clear of the mesh (a region inside it) or move the mesh";
      return e.str();
    }
  }
  return {};
}

std::string MeshWall::description() const {
  std::ostringstream o;
  o << "mesh wall '" << name << "': " << file << ", " << surface->triangles() << " triangles, "
    << surface->boundary_edges() << " open edge(s), " << surface->nonmanifold_edges() << " non-manifold, "
    << (surface->one_sided() ? "one" : "two") << "-sided, " << surface->bytes() / 1e6 << " MB on every rank"
    << (moving ? ", moving" : "");
  return o.str();
}

void MeshWall::near_list(const ParticleStore& p, std::size_t n, double skin, bool shapes, std::vector<std::uint32_t>& out,
                         NearItems& items) const {
  items.start.assign(1, 0);
  items.items.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t before = items.items.size();
    // A sphere's items are marked deep where its centre stays over the face
    // until the next build (it moves less than the skin relative to the
    // wall: the list's trigger). Not an ellipsoid's: they go their own way.
    const bool sphere = !shapes || p.shape[i] != kEllipsoid;
    surface->near(to_body(p.x[i]), p.radius[i] + skin, items.items, nullptr, sphere ? skin : -1.0);
    if (items.items.size() == before) continue;
    out.push_back(static_cast<std::uint32_t>(i));
    items.start.push_back(static_cast<std::uint32_t>(items.items.size()));
  }
}

int MeshWall::ellipsoid_contacts(const ParticleStore& p, std::size_t i, std::span<const std::uint32_t> tris,
                                 contact::MeshContact* out) const {
  const Quat q = moving ? Quat(R.transpose()) * p.orientation[i] : p.orientation[i];
  const contact::Ellipsoid e{to_body(p.x[i]), p.semi_axes[i], q};
  return std::min(contact::ellipsoid_mesh_contacts(*surface, e, tris, out, kMaxFound), kMaxFound);
}

double MeshWall::ellipsoid_depth(const contact::Ellipsoid& e) const {
  thread_local std::vector<std::uint32_t> tris;
  tris.clear();
  const contact::Ellipsoid b{to_body(e.centre), e.semi_axes,
                             moving ? Quat(R.transpose()) * e.orientation : e.orientation};
  surface->near(b.centre, e.semi_axes.maxCoeff(), tris);
  contact::MeshContact c[kMaxFound];
  if (tris.empty() || contact::ellipsoid_mesh_contacts(*surface, b, tris, c, kMaxFound) == 0) return 0;
  return c[0].depth;
}

bool MeshWall::touches(const contact::Ellipsoid& e) const { return ellipsoid_depth(e) > 0; }

bool MeshWall::from_record(const std::vector<double>& v, const WallSurface& cells, MeshWall& w) {
  if (v.size() != 14 || cells.triangles.empty()) return false;
  w.motion_time = v[0];
  w.surface = std::make_shared<contact::MeshSurface>(cells.points, cells.triangles, v[13] != 0);
  return true;
}

}  // namespace grains::sim
