#pragma once
// The Perram-Wertheim (PW85) contact function of two ellipsoids.
//
//   mu^2 = max_{lambda in [0,1]} f(lambda),
//   f(lambda) = lambda (1 - lambda) r^T Q(lambda)^{-1} r,
//   Q(lambda) = (1 - lambda) Q1 + lambda Q2,          r = c2 - c1,
//
// with Q1, Q2 the quadratic forms of ellipsoid.hpp (seed 000 convention).
// mu < 1: the ellipsoids overlap; mu = 1: externally tangent; mu > 1: apart.
// mu is the common factor by which both bodies, scaled about their centres,
// become externally tangent, at x0 = c1 + (1 - lambda) Q1 Q(lambda)^{-1} r.
//
// Method (docs/pw85.md): Newton's method on f'(lambda) = 0 safeguarded by a
// bracket that always contains the maximiser (f is concave, f'(0) > 0 > f'(1)),
// with a bisection fallback. Each step costs one 3x3 LDL^T factorisation of
// Q(lambda) and two triangular solves; f' is evaluated in the form
// (1-l)^2 x^T Q1 x - l^2 x^T Q2 x (x = Q(l)^{-1} r) whose two terms are
// positive. Cold start lambda = h1/(h1+h2) (h_i the support radii along r),
// exact for spheres; warm start from the pair's previous lambda.
#include <Eigen/Core>

#include "contact/ellipsoid/ellipsoid.hpp"

namespace grains::contact {

enum class Pw85Status : int {
  ok = 0,            // converged; mu2, lambda, x0, normal are valid
  separated,         // early exit: some f(lambda) > 1 was found, so the bodies
                     // are apart; mu2 is a lower bound (> 1) of the true value
  not_spd,           // Q1 or Q2 is not (numerically) symmetric positive-definite
  non_finite_input,  // NaN or Inf in Q1, Q2 or r
  not_converged,     // iteration limit hit; mu2 is a lower bound (f at the best lambda)
};

const char* to_string(Pw85Status s);

struct Pw85Options {
  // Warm start: the pair's lambda from the previous time step. Any value outside
  // (0, 1) (the default) asks for the cold start.
  double lambda_guess = -1.0;
  // Return with status `separated` as soon as some f(lambda) > 1 is found.
  bool stop_if_separated = false;
  int max_iterations = 100;
  // Newton stops when the step in u = log(lambda/(1-lambda)) is below this and
  // takes that last step from the derivatives at hand: lambda and the normal
  // are then accurate to ~tolerance^2, mu2 to ~tolerance^3 (relative). The
  // default gives full double precision; the DEM uses a looser value
  // (docs/pw85.md).
  double tolerance = 1e-7;
  // The caller guarantees finite, symmetric positive-definite Q1, Q2 and
  // magnitudes (Q, r, r^T Q r) far from overflow and underflow (e.g. the forms
  // of a DEM scene): skips the input checks and the power-of-two rescaling.
  // A failure to factor Q(lambda) is still reported (not_converged).
  bool trusted_input = false;
};

struct Pw85Result {
  double mu2 = 0.0;  // contact function value (NaN only for invalid input)
  double lambda = 0.5;
  // x0 - c1: the tangency point of the mu-scaled ellipsoids, relative to c1.
  Eigen::Vector3d x0_rel{0, 0, 0};
  // Unit normal at x0 along Q(lambda)^{-1} r: outward for body 1, pointing
  // towards body 2. (0,0,1) when r = 0.
  Eigen::Vector3d normal{0, 0, 1};
  int iterations = 0;  // number of evaluations of f (each: one LDL^T + 2 solves)
  Pw85Status status = Pw85Status::ok;

  bool converged() const { return status == Pw85Status::ok; }
};

// The contact function of ellipsoids (c1, Q1) and (c2, Q2) with r = c2 - c1.
// Never returns NaN for finite SPD input (mu2 may be +Inf when it overflows).
// r = 0 gives mu2 = 0, lambda = 0.5 and status ok.
Pw85Result pw85_contact(const Eigen::Vector3d& r, const SymMat3& q1, const SymMat3& q2,
                        const Pw85Options& options = {});

// True when f(lambda) > 1, i.e. the bodies are proven apart by this one
// lambda: one LDL^T of Q(lambda) and one solve, about half a Newton iteration.
// For trusted input only (see Pw85Options::trusted_input); false when
// Q(lambda) does not factor.
bool pw85_separated_at(double lambda, const Eigen::Vector3d& r, const SymMat3& q1, const SymMat3& q2);

// f(lambda) alone, for tests and diagnostics (no input checks; NaN if
// Q(lambda) is not positive-definite).
double pw85_f(double lambda, const Eigen::Vector3d& r, const SymMat3& q1, const SymMat3& q2);

// True when Q is symmetric positive-definite as seen by an LDL^T factorisation
// (all pivots > 0 and finite).
bool is_spd(const SymMat3& q);

}  // namespace grains::contact
