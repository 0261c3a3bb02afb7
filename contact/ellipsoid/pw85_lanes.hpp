#pragma once
// Many ellipsoid pairs at once: the PW85 contact function and the contact
// geometry of a list of pairs, kLanes pairs in lockstep (lanes.hpp).
//
// The arithmetic per pair is pw85_contact's and contact_geometry_from_pw85's
// (the same kernels, pw85_kernel.hpp), so each pair's result is the one the
// scalar functions give (tested); what changes is the schedule: a pair's
// solve is a chain of dependent divisions and square roots, and running
// kLanes independent chains side by side lets the processor overlap them
// (and use packed SIMD instructions). A lane whose pair is done (most
// persistent contacts converge in one evaluation from their warm start, most
// pairs that are apart are proven so by the first) takes the next pair of
// the list, so lanes stay full while other pairs iterate.
//
// For the DEM's trusted input (finite SPD forms, everyday magnitudes;
// Pw85Options::trusted_input): no input checks and no rescaling.
#include <cstddef>

#include "contact/contact_geometry.hpp"
#include "contact/ellipsoid/pw85.hpp"

namespace grains::contact {

struct Pw85LaneJob {
  const double* qi;     // packed form of body i (6 doubles)
  const double* qj;     // packed form of body j
  double r[3];          // c_j - c_i
  double lambda_guess;  // warm start in (0, 1), anything else: cold
};

struct Pw85LaneResult {
  Pw85Status status;  // ok, separated or not_converged
  double mu2;         // as Pw85Result::mu2 (a lower bound unless ok)
  double lambda;
  double x[3];        // Q(lambda)^{-1} r: the normal's direction, unnormalised
};

// pw85_contact(r, qi, qj, opt) for jobs[0..count) with opt.trusted_input,
// opt.stop_if_separated = stop_if_separated, opt.tolerance = tolerance.
void pw85_contact_lanes(const Pw85LaneJob* jobs, std::size_t count, Pw85LaneResult* out, double tolerance,
                        bool stop_if_separated, int max_iterations = 100);

struct PairGeometryJob {
  const double* ci;  // centre of body i (3 doubles)
  const double* qi;
  const double* cj;
  const double* qj;
  double x[3];  // a Pw85LaneResult's x (from i towards j)
};

// contact_geometry_from_pw85 for jobs[0..count).
void contact_geometry_lanes(const PairGeometryJob* jobs, std::size_t count, ContactGeometry* out);

// The instruction set of the copy in use: "avx2" (x86-64 CPUs with AVX2) or
// "baseline" (others, or GRAINS_SIMD=baseline). Both give the same bits.
const char* lanes_instruction_set();

}  // namespace grains::contact
