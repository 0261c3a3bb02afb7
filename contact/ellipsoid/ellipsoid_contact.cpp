// Ellipsoid-ellipsoid contact geometry: see ellipsoid_contact.hpp.
#include "contact/ellipsoid/ellipsoid_contact.hpp"

#include <cmath>

#include "contact/ellipsoid/surface_curvature.hpp"

namespace grains::contact {

using Eigen::Vector3d;

ContactGeometry contact_geometry_from_pw85(const Vector3d& ci, const SymMat3& qi, const Vector3d& cj,
                                           const SymMat3& qj, const Pw85Result& pw85) {
  const Vector3d& n = pw85.normal;  // from i towards j
  const Vector3d qin = form_times(qi, n), qjn = form_times(qj, n);
  const double hi2 = n.dot(qin), hj2 = n.dot(qjn);
  const double hi = std::sqrt(hi2), hj = std::sqrt(hj2);
  const Vector3d pi = ci + qin * (1.0 / hi), pj = cj - qjn * (1.0 / hj);
  ContactGeometry g;
  g.normal = -n;
  g.overlap = hi + hj - (cj - ci).dot(n);
  g.point = 0.5 * (pi + pj);
  Vector3d t1, t2;
  tangent_basis(n, t1, t2);
  g.radius = hertz_radius_of_pair(qi, qin, hi2, hi, qj, qjn, hj2, hj, t1, t2);
  return g;
}

EllipsoidPairContact ellipsoid_contact(const Vector3d& ci, const SymMat3& qi, const Vector3d& cj,
                                       const SymMat3& qj, double lambda_guess) {
  EllipsoidPairContact c;
  Pw85Options opt;
  opt.lambda_guess = lambda_guess;
  opt.stop_if_separated = true;
  c.pw85 = pw85_contact(cj - ci, qi, qj, opt);
  if (c.pw85.status != Pw85Status::ok) return c;
  c.geometry = contact_geometry_from_pw85(ci, qi, cj, qj, c.pw85);
  c.touching = c.pw85.mu2 < 1.0;
  return c;
}

}  // namespace grains::contact
