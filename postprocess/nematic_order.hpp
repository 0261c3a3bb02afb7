#pragma once
// Nematic (orientational) order of elongated or flattened particles.
//
// Each particle contributes a unit axis u (a body axis rotated to the world
// frame by its orientation quaternion). The order tensor is
//     Q = (1/N) sum (3/2 u u^T - 1/2 I),
// traceless and symmetric; S is its largest eigenvalue and the director its
// eigenvector. S = 1 when all axes are parallel (or antiparallel: u and -u are
// the same axis); S -> 0 for an isotropic distribution of many particles; axes
// spread isotropically within a plane give eigenvalues (-1/2, 1/4, 1/4), so
// S = 1/4 and the plane normal is the eigenvector of -1/2 (reported in
// `eigenvalues`). With finitely many random axes S
// is positive, of order 1/sqrt(N): `isotropic_baseline` is the mean S of
// isotropic samples of the same N, to judge whether a measured S means order.
#include <vector>

#include "postprocess/frame.hpp"
#include "postprocess/packing_fraction.hpp"

namespace grains::postprocess {

struct NematicOrder {
  double S = 0;
  Vec3 director{0, 0, 1};
  Vec3 eigenvalues{0, 0, 0};  // ascending
  std::size_t n = 0;
  int axis = 0;                   // body axis used (0, 1, 2)
  double isotropic_baseline = 0;  // mean S of 32 isotropic samples of n axes
};

/// Order of the given unit axes.
NematicOrder nematic_order(const std::vector<Vec3>& axes);

/// The body axis that describes a particle's shape: for spheroids the symmetry
/// axis (the semi-axis farthest from the mean of the other two: the long axis of
/// a prolate, the short axis of an oblate one); without semi_axes, body axis 0.
int shape_axis(const Vec3& semi_axes);

/// Order of the particles whose centre lies in `region`; `axis` < 0 picks
/// shape_axis() of the first selected particle. Requires orientations.
NematicOrder nematic_order(const Frame& f, const Box& region, int axis = -1);

}  // namespace grains::postprocess
