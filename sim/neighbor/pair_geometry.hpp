#pragma once
// The contact geometry of one neighbour-list pair of any shapes: sphere-
// sphere (closed form), sphere-ellipsoid (closest point on the ellipsoid,
// contact/ellipsoid/point_ellipsoid.hpp) or ellipsoid-ellipsoid (PW85,
// contact/ellipsoid/ellipsoid_contact.hpp). Geometry only: the ellipsoid pair
// stage (sim/laws/ellipsoid_pair_stage.hpp) applies the law to it, the VTK
// output counts contacts with it.
#include "contact/ellipsoid/ellipsoid_contact.hpp"
#include "contact/ellipsoid/point_ellipsoid.hpp"
#include "contact/sphere.hpp"
#include "sim/state/particle_store.hpp"

namespace grains::sim {

/// PW85 tolerance in the DEM (Pw85Options::tolerance): the step in
/// u = log(lambda/(1-lambda)) below which Newton stops. It leaves relative
/// errors ~1e-8 in lambda and the normal and ~1e-12 in mu^2, i.e. ~1e-9 of a
/// typical overlap (delta/|r| ~ 1e-3), and lets a warm-started persistent
/// contact finish in one or two factorisations (docs/pw85.md).
inline constexpr double kPw85DemTolerance = 1e-4;

/// Separating axis along the line of centres r = x_j - x_i (r2 = |r|^2): true
/// if the two bodies' shadows on that line do not overlap (support radii
/// h = sqrt(u^T Q u), u = r/|r|), i.e. the bodies are apart. Two matrix-vector
/// products, far cheaper than a PW85 solve, and it rejects most pairs whose
/// bounding spheres overlap. With a = r^T Q_i r = (h_i |r|)^2 (a_i^2 |r|^2
/// for a sphere), likewise b, and c = |r|^2 the test h_i + h_j <= |r| reads
/// sqrt(a) + sqrt(b) <= c, i.e. d = c^2 - a - b >= 0 and 4 a b <= d^2: no
/// square root.
inline bool apart_along_centres(const ParticleStore& p, std::size_t i, std::size_t j, bool ei, bool ej, const Vec3& r,
                                double r2) {
  if (!(r2 > 0)) return false;
  const double a = ei ? r.dot(contact::form_times(p.form[i], r)) : p.radius[i] * p.radius[i] * r2;
  const double b = ej ? r.dot(contact::form_times(p.form[j], r)) : p.radius[j] * p.radius[j] * r2;
  const double d = r2 * r2 - a - b;
  return d >= 0 && 4 * a * b <= d * d;
}

/// Geometry of the pair (i, j) for any shapes; `lambda` is the PW85 warm start
/// (in/out; < 0: cold). Returns false when the bodies do not touch.
/// `maybe_apart`: the pair probably did not touch at the previous step (first
/// try to prove it apart at the warm-start lambda); a hint, the result does
/// not depend on it.
inline bool shape_pair_geometry(const ParticleStore& p, std::size_t i, std::size_t j, double& lambda,
                                contact::ContactGeometry& g, bool maybe_apart = true) {
  const bool ei = p.shape[i] == kEllipsoid, ej = p.shape[j] == kEllipsoid;
  if (!ei && !ej) return contact::sphere_sphere(p.x[i], p.radius[i], p.x[j], p.radius[j], g);
  const Vec3 r = p.x[j] - p.x[i];
  if (apart_along_centres(p, i, j, ei, ej, r, r.squaredNorm())) return false;
  if (ei && ej) {
    // A pair that was apart at the previous step usually still is at the same
    // lambda: f(lambda) > 1 proves it with half a PW85 iteration.
    if (maybe_apart && lambda > 0.0 && lambda < 1.0 && contact::pw85_separated_at(lambda, r, p.form[i], p.form[j]))
      return false;
    // PW85 with early exit and warm start at the DEM tolerance (kPw85DemTolerance);
    // the contact geometry (support points, curvatures, R*) only for pairs that touch.
    contact::Pw85Options opt;
    opt.lambda_guess = lambda;
    opt.stop_if_separated = true;
    opt.trusted_input = true;  // forms of positive semi-axes, built every step
    opt.tolerance = kPw85DemTolerance;
    const auto pw = contact::pw85_contact(r, p.form[i], p.form[j], opt);
    if (pw.status == contact::Pw85Status::ok || pw.status == contact::Pw85Status::separated)
      lambda = pw.lambda;
    if (pw.status != contact::Pw85Status::ok || !(pw.mu2 < 1.0)) return false;
    g = contact::contact_geometry_from_pw85(p.x[i], p.form[i], p.x[j], p.form[j], pw);
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

}  // namespace grains::sim
