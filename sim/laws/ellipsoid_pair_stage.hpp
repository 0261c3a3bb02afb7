#pragma once
// Contacts in scenes with ellipsoids: the same Law as for spheres, with the
// geometry chosen per pair from the shapes: sphere-sphere (closed form),
// sphere-ellipsoid (closest point on the ellipsoid, contact/ellipsoid/
// point_ellipsoid.hpp) or ellipsoid-ellipsoid (PW85, contact/ellipsoid/
// ellipsoid_contact.hpp). The PW85 lambda of each pair is kept after the
// law's history and warm-starts the next step's solve. Scenes of spheres
// only never instantiate this stage.
#include <algorithm>

#include "contact/ellipsoid/ellipsoid_contact.hpp"
#include "contact/ellipsoid/point_ellipsoid.hpp"
#include "contact/sphere.hpp"
#include "sim/laws/contact_law.hpp"
#include "sim/scene/stage.hpp"

namespace grains::sim {

/// Geometry of the pair (i, j) for any shapes; `lambda` is the PW85 warm start
/// (in/out; < 0: cold). Returns false when the bodies do not touch.
inline bool shape_pair_geometry(const ParticleStore& p, std::size_t i, std::size_t j, double& lambda,
                                contact::ContactGeometry& g) {
  const bool ei = p.shape[i] == kEllipsoid, ej = p.shape[j] == kEllipsoid;
  if (!ei && !ej) return contact::sphere_sphere(p.x[i], p.radius[i], p.x[j], p.radius[j], g);
  // Separating axis along the line of centres: if the two shadows on that
  // line do not overlap (support radii h = sqrt(u^T Q u)), the bodies are
  // apart. Two matrix-vector products, far cheaper than a PW85 solve, and it
  // rejects most pairs whose bounding spheres overlap.
  const Vec3 r = p.x[j] - p.x[i];
  const double r2 = r.squaredNorm();
  if (r2 > 0) {
    const Vec3 u = r / std::sqrt(r2);
    const double hi = ei ? std::sqrt(u.dot(contact::form_times(p.form[i], u))) : p.radius[i];
    const double hj = ej ? std::sqrt(u.dot(contact::form_times(p.form[j], u))) : p.radius[j];
    if ((hi + hj) * (hi + hj) <= r2) return false;
  }
  if (ei && ej) {
    const auto c = contact::ellipsoid_contact(p.x[i], p.form[i], p.x[j], p.form[j], lambda);
    if (c.pw85.status == contact::Pw85Status::ok || c.pw85.status == contact::Pw85Status::separated)
      lambda = c.pw85.lambda;
    if (!c.touching) return false;
    g = c.geometry;
    return g.overlap > 0;
  }
  // One sphere, one ellipsoid: geometry with the ellipsoid as body j, then
  // flipped if the ellipsoid is i.
  const std::size_t s = ei ? j : i, e = ei ? i : j;
  contact::Ellipsoid body{p.x[e], p.semi_axes[e], p.orientation[e]};
  bool touching = false;
  g = contact::sphere_ellipsoid_contact(p.x[s], p.radius[s], body, &touching);
  if (!touching || !(g.overlap > 0)) return false;
  if (ei) g.normal = -g.normal;
  return true;
}

template <class Law>
class ShapePairContactStage final : public Stage {
 public:
  std::string name() const override { return "force.pair_contacts[sphere|ellipsoid]<" + Law::name() + ">"; }
  Phase phase() const override { return Phase::Force; }

  void run(Scene& s) override {
    ParticleStore& p = s.particles;
    NeighborList& nl = s.neighbors;
    constexpr int H = Law::history_size;
    constexpr int NH = H + 1;  // + PW85 lambda
    const double dt = s.clock.dt;
    const std::size_t rows = nl.row_start.empty() ? 0 : nl.row_start.size() - 1;
    for (std::size_t i = 0; i < rows; ++i) {
      for (auto k = nl.row_start[i]; k < nl.row_start[i + 1]; ++k) {
        const std::size_t j = nl.partner[k];
        double* hist = nl.history.data() + static_cast<std::size_t>(k) * NH;
        const auto& pc = nl.pair_constants[k];
        if ((p.x[i] - p.x[j]).squaredNorm() >= pc.contact2) {  // bounding spheres apart
          std::fill_n(hist, NH, 0.0);
          hist[H] = -1.0;
          continue;
        }
        double lambda = hist[H] > 0 ? hist[H] : -1.0;
        contact::ContactGeometry g;
        const bool touching = shape_pair_geometry(p, i, j, lambda, g);
        hist[H] = lambda;
        if (!touching) {
          if constexpr (H > 0) std::fill_n(hist, H, 0.0);
          continue;
        }
        const PairParams& pp = s.pairs(p.material[i], p.material[j]);
        const Vec3 ci = g.point - p.x[i], cj = g.point - p.x[j];
        const Vec3 v_rel = p.v[i] + p.omega[i].cross(ci) - p.v[j] - p.omega[j].cross(cj);
        const Vec3 w_rel = p.omega[i] - p.omega[j];
        const auto r = Law::evaluate(g, v_rel, w_rel, pc.mass, pp, dt, hist);
        p.f[i] += r.force;
        p.f[j] -= r.force;
        p.torque[i] += ci.cross(r.force) + r.rolling_torque;
        p.torque[j] -= cj.cross(r.force) + r.rolling_torque;
      }
    }
  }
};

}  // namespace grains::sim
