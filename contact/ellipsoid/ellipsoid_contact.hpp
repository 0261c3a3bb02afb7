#pragma once
// Ellipsoid-ellipsoid contact geometry for the DEM, from the PW85 solution.
//
// PW85 (pw85.hpp) gives mu and the common unit normal n of the two bodies
// scaled by mu about their centres, which touch at x0. Scaling about a centre
// preserves normals, so the points of the *unscaled* surfaces with normal
// +n (body i) and -n (body j) are the support points
//     p_i = c_i + Q_i n / h_i,   p_j = c_j - Q_j n / h_j,   h = sqrt(n^T Q n),
// (p_i = c_i + (x0 - c_i)/mu, likewise p_j) and the depth along n is
//     overlap = (p_i - p_j).n = h_i + h_j - r.n = (1/mu - 1) r.n,
// the support-function identity of the PW85 literature (exact for spheres:
// a_i + a_j - |r|). This is the overlap of the two bodies' projections on the
// common normal; it agrees with the true penetration depth to first order in
// the overlap. The contact point is the midpoint of p_i and p_j, and R* comes
// from both surfaces' curvature tensors at p_i and p_j (surface_curvature.hpp;
// hertz_radius_of_pair: the determinant of their sum with one division).
// The support-point form is used (not x0/mu) so that r = 0 and mu -> 0 stay finite.
#include <Eigen/Core>

#include "contact/contact_geometry.hpp"
#include "contact/ellipsoid/ellipsoid.hpp"
#include "contact/ellipsoid/pw85.hpp"

namespace grains::contact {

struct EllipsoidPairContact {
  bool touching = false;     // PW85 converged and mu^2 < 1
  ContactGeometry geometry;  // filled when the solver converged (also if not touching)
  Pw85Result pw85;           // raw solver output; keep pw85.lambda for the warm start
};

// Geometry of bodies i = (ci, qi) and j = (cj, qj) from a PW85 result computed
// with r = cj - ci, q1 = qi, q2 = qj. Normal points from j towards i.
ContactGeometry contact_geometry_from_pw85(const Eigen::Vector3d& ci, const SymMat3& qi,
                                           const Eigen::Vector3d& cj, const SymMat3& qj,
                                           const Pw85Result& pw85);

// The DEM entry point: PW85 with early exit (a separated pair costs one or two
// evaluations) and optional warm start from the pair's lambda of the previous
// step (pass a value outside (0,1) for a cold start).
EllipsoidPairContact ellipsoid_contact(const Eigen::Vector3d& ci, const SymMat3& qi,
                                       const Eigen::Vector3d& cj, const SymMat3& qj,
                                       double lambda_guess = -1.0);

inline EllipsoidPairContact ellipsoid_contact(const Ellipsoid& i, const Ellipsoid& j,
                                              double lambda_guess = -1.0) {
  return ellipsoid_contact(i.centre, i.form(), j.centre, j.form(), lambda_guess);
}

}  // namespace grains::contact
