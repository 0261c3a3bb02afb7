#pragma once
#include "contact/contact_geometry.hpp"
// Cohesion slot.
//  * NoCohesion.
//  * SjkrCohesion: simplified JKR; an attractive normal force k_c A over the
//    contact area A = 2 pi R* d (the area of the overlap circle to first order
//    in d, exact in the limit for sphere-sphere and sphere-plane), acting only
//    while the bodies overlap. It is subtracted after the clamp of the
//    repulsive Hertz force, so the net normal force can be attractive; the
//    Coulomb and rolling limits use the repulsive part.
// Case-file key: materials[].cohesion_energy_density (J/m^3).
#include <cmath>

#include "sim/laws/pair_params.hpp"

namespace grains::sim {

struct NoCohesion {
  static constexpr const char* name = "none";
  static GRAINS_INLINE double force(double, double, const PairParams&) { return 0.0; }
};

struct SjkrCohesion {
  static constexpr const char* name = "sjkr";
  /// Attractive force magnitude (>= 0) for overlap d and effective radius R.
  static GRAINS_INLINE double force(double d, double R, const PairParams& p) { return p.cohesion * 2.0 * M_PI * R * d; }
};

}  // namespace grains::sim
