// Ellipsoid-ellipsoid contact geometry: see ellipsoid_contact.hpp.
#include "contact/ellipsoid/ellipsoid_contact.hpp"

#include <cmath>

#include "contact/ellipsoid/surface_curvature.hpp"

namespace grains::contact {

using Eigen::Vector3d;

ContactGeometry contact_geometry_from_pw85(const Vector3d& ci, const SymMat3& qi, const Vector3d& cj,
                                           const SymMat3& qj, const Pw85Result& pw85) {
  pw85_kernel::PairGeometry<double> pg;
  pw85_kernel::pair_geometry(ci.data(), qi.data(), cj.data(), qj.data(), pw85.normal.data(), pg);
  ContactGeometry g;
  g.normal = {pg.normal[0], pg.normal[1], pg.normal[2]};
  g.overlap = pg.overlap;
  g.point = {pg.point[0], pg.point[1], pg.point[2]};
  g.radius = pg.radius;
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
