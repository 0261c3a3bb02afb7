#pragma once
// The one thing contact/ hands to the force laws in sim/laws: where two bodies
// touch, along which normal, how deep, and the curvature the Hertz law needs.
// Spheres, walls, ellipsoids and clump balls all reduce to this struct, so the
// laws never know what shape produced it.
#include <Eigen/Core>

// Hot geometry and law kernels are forced inline into the contact loops.
#ifndef GRAINS_INLINE
#define GRAINS_INLINE inline __attribute__((always_inline))
#endif

namespace grains::contact {

using Vec3 = Eigen::Vector3d;

struct ContactGeometry {
  Vec3 normal{0, 0, 1};  // unit normal pointing from body j towards body i:
                         // a repulsive normal force acts on i along +normal
  double overlap = 0.0;  // penetration depth (> 0 means touching), metres
  Vec3 point{0, 0, 0};   // contact point in the world frame
  double radius = 0.0;   // effective radius of curvature R* for the Hertz law
};

}  // namespace grains::contact
