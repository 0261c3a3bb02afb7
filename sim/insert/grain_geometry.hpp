#pragma once
// The geometry of a grain to be inserted, in the two forms insertion needs:
//  * its parts in world coordinates for the exact contact check (spheres: a
//    sphere or a clump's balls; or one ellipsoid as its PW85 form);
//  * balls that cover it, in its body frame about its reference point (the
//    centre, or a clump's centre of mass), for the overlap field of the NFFT
//    (contact/correlation/overlap_field.hpp). Spheres and clumps are their own
//    cover; an ellipsoid is covered conservatively by balls along its longest
//    axis (ellipsoid_cover).
#include <vector>

#include "contact/ellipsoid/ellipsoid.hpp"
#include "sim/scene/scene_config.hpp"

namespace grains::sim::insert {

struct GrainParts {
  std::vector<Vec3> centres;  // spheres (empty for an ellipsoid)
  std::vector<double> radii;
  bool ellipsoid = false;
  Vec3 ell_centre{0, 0, 0};
  contact::SymMat3 form{};  // PW85 form R diag(a^2) R^T
  double ell_bound = 0;     // largest semi-axis
  Vec3 ell_axes{0, 0, 0};   // semi-axes (body frame)
  Quat ell_orientation = Quat::Identity();
};

/// The grain of shape `shape` with bounding radius q, reference point at x, orientation o.
GrainParts grain_parts(const ShapeConfig& shape, double q, const Vec3& x, const Quat& o);

/// Balls whose union contains the ellipsoid with semi-axes `axes` (body
/// frame, centred at 0). The body is cut into n slabs across its longest axis
/// (n = ceil(1.5 a_max / b), b the larger of the other two semi-axes); the
/// ball of a slab sits on the axis at the slab's middle and reaches the
/// farthest point of the slab: the ellipsoid's section at abscissa x lies
/// within radius b sqrt(1 - x^2/a^2) of the axis, and (x - x_k)^2 + b^2 (1 -
/// x^2/a^2) is convex in x, so its maximum over the slab is at an end. For
/// aspect ratio 2 the balls' union holds about 1.9 times the ellipsoid's
/// volume; an oblate body (two equal long axes) is covered by slabs across
/// one of them and fits more loosely.
void ellipsoid_cover(const Vec3& axes, std::vector<Vec3>& centres, std::vector<double>& radii);

/// The cover balls of a grain of bounding radius q in its body frame.
void cover_balls(const ShapeConfig& shape, double q, std::vector<Vec3>& centres, std::vector<double>& radii);

}  // namespace grains::sim::insert
