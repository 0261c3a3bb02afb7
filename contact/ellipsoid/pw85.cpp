// PW85 contact function: safeguarded Newton on f'(lambda) = 0. See pw85.hpp
// for the problem and docs/pw85.md for the method and its measured accuracy.
#include "contact/ellipsoid/pw85.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace grains::contact {

using Eigen::Vector3d;

const char* to_string(Pw85Status s) {
  switch (s) {
    case Pw85Status::ok: return "ok";
    case Pw85Status::separated: return "separated";
    case Pw85Status::not_spd: return "not symmetric positive-definite";
    case Pw85Status::non_finite_input: return "non-finite input";
    case Pw85Status::not_converged: return "not converged";
  }
  return "unknown";
}

namespace {


// Q = L D L^T of a packed symmetric 3x3 matrix (L unit lower triangular);
// the reciprocal pivots are kept so that the solves need no division.
struct Ldl {
  double i0, i1, i2, l10, l20, l21;  // 1/d0, 1/d1, 1/d2, L
};

// Returns false unless all three pivots are positive and finite.
inline bool factor(const double* q, Ldl& f) {
  const double d0 = q[0];
  if (!(d0 > 0.0)) return false;
  f.i0 = 1.0 / d0;
  f.l10 = q[1] * f.i0;
  f.l20 = q[2] * f.i0;
  const double d1 = q[3] - f.l10 * q[1];
  if (!(d1 > 0.0)) return false;
  f.i1 = 1.0 / d1;
  const double e = q[4] - f.l20 * q[1];  // = d1 * l21
  f.l21 = e * f.i1;
  const double d2 = q[5] - f.l20 * q[2] - f.l21 * e;
  if (!(d2 > 0.0 && d2 < std::numeric_limits<double>::infinity())) return false;
  f.i2 = 1.0 / d2;
  return true;
}

// x = Q^{-1} b; also returns b^T Q^{-1} b = sum y_i^2 / d_i (>= 0 by construction).
inline Vector3d solve(const Ldl& f, const Vector3d& b, double& bqb) {
  const double y0 = b[0];
  const double y1 = b[1] - f.l10 * y0;
  const double y2 = b[2] - f.l20 * y0 - f.l21 * y1;
  const double z0 = y0 * f.i0, z1 = y1 * f.i1, z2 = y2 * f.i2;
  bqb = y0 * z0 + y1 * z1 + y2 * z2;
  Vector3d x;
  x[2] = z2;
  x[1] = z1 - f.l21 * x[2];
  x[0] = z0 - f.l10 * x[1] - f.l20 * x[2];
  return x;
}

inline Vector3d mul(const double* q, const Vector3d& v) {
  return {q[0] * v[0] + q[1] * v[1] + q[2] * v[2], q[1] * v[0] + q[3] * v[1] + q[4] * v[2],
          q[2] * v[0] + q[4] * v[1] + q[5] * v[2]};
}

bool all_finite(const double* p, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(p[i])) return false;
  return true;
}

// Everything one evaluation at lambda yields. With x = Q(l)^{-1} r,
// a = x^T Q1 x, b = x^T Q2 x, the two terms of the envelope identity
// (seed 000, eq. 13) are A1 = (1-l)^2 a and A2 = l^2 b, f = l A1 + (1-l) A2
// and f' = A1 - A2.
struct Eval {
  double f, df;       // f, f' with respect to lambda
  double step;        // Newton step -ell/ell' in u = log(l/(1-l)), ell = log(A1/A2)
                      // (+inf when ell' >= 0 or not finite: bisect instead)
  double g, t, a, b;  // r^T x, v^T Q^{-1} v with v = (Q2-Q1) x, a, b: for f''
  Vector3d x;         // Q(lambda)^{-1} r
  Vector3d w;         // Q(lambda)^{-1} (Q2 - Q1) x  (so dx/dlambda = -w)
};

// log(A1/A2) from z = (A1 - A2)/(A1 + A2) = tanh(ell/2): ell = 2 atanh(z).
// Near the root (|z| small, every iteration but the first one or two) the
// series of atanh replaces the call to log; its relative error (< 1e-11 for
// |z| < 0.1, < 2e-13 for |z| < 1e-2) only perturbs the Newton step by that
// fraction of itself, which keeps the convergence quadratic.
inline double log_ratio(double a1, double a2, double d) {
  const double z = d / (a1 + a2);
  const double z2 = z * z;
  if (z2 < 1e-4) return 2.0 * z * (1.0 + z2 * (1.0 / 3.0 + z2 * 0.2));
  if (z2 < 1e-2) return 2.0 * z * (1.0 + z2 * (1.0 / 3.0 + z2 * (0.2 + z2 * (1.0 / 7.0 + z2 * (1.0 / 9.0)))));
  return std::log(a1 / a2);
}

// exp(s) for the Newton update of t = lambda/(1-lambda); the Taylor form for
// small steps (relative error < 3e-9 for |s| < 0.05: the new point moves by
// that much in u, far less than the Newton error it leaves).
inline double exp_step(double s) {
  if (std::abs(s) < 0.05) return 1.0 + s * (1.0 + s * (0.5 + s * (1.0 / 6.0 + s * (1.0 / 24.0))));
  return std::exp(s);
}

// lam and lc = 1 - lam are passed separately so that both keep full relative
// precision near either end. Returns false when Q(lambda) is numerically singular.
inline bool evaluate(double lam, double lc, const Vector3d& r, const double* q1, const double* q2,
                     Eval& e) {
  double q[6];
  for (int i = 0; i < 6; ++i) q[i] = lc * q1[i] + lam * q2[i];
  Ldl fac;
  if (!factor(q, fac)) return false;
  e.x = solve(fac, r, e.g);
  const Vector3d q1x = mul(q1, e.x), q2x = mul(q2, e.x);
  const double a = e.x.dot(q1x), b = e.x.dot(q2x);
  e.a = a;
  e.b = b;
  const double ll = lam * lc;
  e.f = ll * e.g;
  const double a1 = lc * lc * a, a2 = lam * lam * b;
  e.df = a1 - a2;
  e.w = solve(fac, q2x - q1x, e.t);
  // ell' = D / (a b) with D = 2 l (1-l) (a (Q2 x).w - b (Q1 x).w) - 2 a b, and
  // near the root ell = 2 atanh(z), z = f'/(A1 + A2): one division gives both
  // z and the step -ell/ell' = -ell a b (A1 + A2) / ((A1 + A2) D).
  const double sum = a1 + a2;
  const double d = 2.0 * ll * (q2x.dot(e.w) * a - q1x.dot(e.w) * b) - 2.0 * a * b;
  const double inv = 1.0 / (sum * d);
  const double abs_inv = a * b * sum * inv;  // = 1 / ell'
  if (a > 0.0 && b > 0.0 && d < 0.0 && std::isfinite(abs_inv) && abs_inv != 0.0) {
    const double z = e.df * d * inv;
    const double z2 = z * z;
    double ell;
    if (z2 < 1e-4)
      ell = 2.0 * z * (1.0 + z2 * (1.0 / 3.0 + z2 * 0.2));
    else if (z2 < 1e-2)
      ell = 2.0 * z * (1.0 + z2 * (1.0 / 3.0 + z2 * (0.2 + z2 * (1.0 / 7.0 + z2 * (1.0 / 9.0)))));
    else
      ell = std::log(a1 / a2);
    e.step = -ell * abs_inv;
  } else {
    // Degenerate magnitudes (a or b zero, or products out of range): the
    // straightforward formulas.
    const double iab = 1.0 / (a * b);
    const double ell = (a > 0.0 && b > 0.0) ? log_ratio(a1, a2, e.df) : (e.df > 0.0 ? 1.0 : -1.0);
    const double dell = -2.0 + 2.0 * ll * (q2x.dot(e.w) * a - q1x.dot(e.w) * b) * iab;
    e.step = dell < 0.0 ? -ell / dell : std::numeric_limits<double>::infinity();
  }
  return true;
}

// f''(lambda) from the quantities of an evaluation.
inline double second_derivative(double lam, double lc, const Eval& e) {
  return -2.0 * e.g - 2.0 * (lc - lam) * (e.b - e.a) + 2.0 * lam * lc * e.t;
}

Pw85Result invalid(Pw85Status s) {
  Pw85Result res;
  res.mu2 = std::numeric_limits<double>::quiet_NaN();
  res.lambda = std::numeric_limits<double>::quiet_NaN();
  res.status = s;
  return res;
}

}  // namespace

bool is_spd(const SymMat3& q) {
  Ldl f;
  if (!all_finite(q.data(), 6)) return false;
  return factor(q.data(), f);
}

double pw85_f(double lambda, const Vector3d& r, const SymMat3& q1, const SymMat3& q2) {
  Eval e;
  if (!evaluate(lambda, 1.0 - lambda, r, q1.data(), q2.data(), e)) return std::numeric_limits<double>::quiet_NaN();
  return e.f;
}

bool pw85_separated_at(double lambda, const Vector3d& r, const SymMat3& q1, const SymMat3& q2) {
  const double lc = 1.0 - lambda;
  double q[6];
  for (int i = 0; i < 6; ++i) q[i] = lc * q1[i] + lambda * q2[i];
  Ldl fac;
  if (!factor(q, fac)) return false;
  double g;
  solve(fac, r, g);
  return lambda * lc * g > 1.0;
}

Pw85Result pw85_contact(const Vector3d& r_in, const SymMat3& q1_in, const SymMat3& q2_in,
                        const Pw85Options& opt) {
  if (!opt.trusted_input &&
      (!all_finite(q1_in.data(), 6) || !all_finite(q2_in.data(), 6) || !all_finite(r_in.data(), 3)))
    return invalid(Pw85Status::non_finite_input);
  Pw85Result res;

  // Exact power-of-two rescaling when the data would over/underflow: with
  // Q -> 4^k Q, r -> 2^k r the contact function and lambda are unchanged, and
  // r -> 2^m r multiplies mu2 by 4^m. Skipped for everyday magnitudes.
  double q1[6], q2[6];
  std::copy(q1_in.begin(), q1_in.end(), q1);
  std::copy(q2_in.begin(), q2_in.end(), q2);
  Vector3d r = r_in;
  int shift_r = 0;  // total exponent applied to r (undo on mu2 and x0)
  int shift_m = 0;  // the part of it that changes mu2 (m above)
  if (opt.trusted_input) {
    if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0) {
      res.mu2 = 0.0;
      res.lambda = 0.5;
      return res;
    }
  } else {
    const double qs = std::max({std::abs(q1[0]), std::abs(q1[3]), std::abs(q1[5]), std::abs(q2[0]),
                                std::abs(q2[3]), std::abs(q2[5])});
    if (!(qs > 0.0)) return invalid(Pw85Status::not_spd);
    constexpr double big = 0x1p200, small = 0x1p-200;
    if (qs > big || qs < small) {
      const int k = -(std::ilogb(qs) / 2);
      for (int i = 0; i < 6; ++i) {
        q1[i] = std::ldexp(q1[i], 2 * k);
        q2[i] = std::ldexp(q2[i], 2 * k);
      }
      for (int i = 0; i < 3; ++i) r[i] = std::ldexp(r[i], k);
      shift_r += k;
    }
    Ldl f1, f2;
    if (!factor(q1, f1) || !factor(q2, f2)) return invalid(Pw85Status::not_spd);
    if (r[0] == 0.0 && r[1] == 0.0 && r[2] == 0.0) {
      res.mu2 = 0.0;  // coincident centres; f = 0 for every lambda
      res.lambda = 0.5;
      return res;
    }
    const double rs = r.cwiseAbs().maxCoeff();
    if (rs > big || rs < small) {
      const int m = -std::ilogb(rs);
      for (int i = 0; i < 3; ++i) r[i] = std::ldexp(r[i], m);
      shift_r += m;
      shift_m = m;
    }
  }
  // f > 1 proves the bodies apart (in the units of the rescaled r).
  const double separated_above = shift_m == 0 ? 1.0 : std::ldexp(1.0, 2 * shift_m);

  // Newton's method on ell(u) = log(A1/A2) = 0 in the logit variable
  // u = log(lambda/(1-lambda)): for two spheres ell is linear in u (one step),
  // and maximisers hugging lambda = 0 or 1 (elongated bodies) stay well scaled.
  // ell has the sign of f', so [u_lo, u_hi] always brackets the maximiser
  // (f concave, f'(0) > 0 > f'(1)); a step leaving it, or one that fails to
  // halve the previous one, is replaced by bisection. The iterate is carried
  // as t = e^u = lambda/(1-lambda) (lambda = t/(1+t), 1-lambda = 1/(1+t), both
  // to full relative precision), so that a step multiplies t by e^du and
  // bisection in u is a geometric mean in t: no log or exp near convergence.
  double t;
  double lam = 0.5, lc = 0.5;
  // A warm start evaluates at the guess itself; t = lambda/(1-lambda) is
  // formed only if the iteration goes on (a persistent contact usually ends
  // after this one evaluation: two divisions fewer on its path).
  const bool warm = opt.lambda_guess > 0.0 && opt.lambda_guess < 1.0;
  if (warm) {
    lam = opt.lambda_guess;
    lc = 1.0 - opt.lambda_guess;
    t = -1.0;  // not formed yet
  } else {
    // Cold start: the exact answer for two spheres of radii h1, h2 (the
    // support radii of the bodies along r), t = h1/h2.
    // (After the rescaling above |r| and |Q| lie within 2^+-200: no overflow.)
    t = std::sqrt(r.dot(mul(q1, r)) / r.dot(mul(q2, r)));
  }
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double tol_u = opt.tolerance;  // default 1e-7: quadratic convergence, next error ~ 1e-14
  constexpr double e4 = 54.598150033144236;  // e^4
  double t_lo = 0.0, t_hi = inf, last_step = inf;

  Eval e;
  Pw85Status status = Pw85Status::not_converged;
  double best_f = 0.0;  // f >= 0 everywhere: always a valid lower bound
  int it = 0;
  while (it < opt.max_iterations) {
    ++it;
    if (t >= 0.0) {
      lc = 1.0 / (1.0 + t);
      lam = t * lc;
    }
    if (!evaluate(lam, lc, r, q1, q2, e)) {
      // Q(lambda) is a convex combination of SPD matrices: this only happens
      // for pairs too ill-conditioned for double precision.
      status = Pw85Status::not_converged;
      break;
    }
    best_f = std::max(best_f, e.f);
    if (opt.stop_if_separated && e.f > separated_above) {
      status = Pw85Status::separated;
      break;
    }
    if (e.df == 0.0) {
      status = Pw85Status::ok;
      break;
    }
    const double step = e.step;
    if (std::abs(step) <= tol_u) {
      // Take this last step with the derivatives at hand instead of another
      // factorisation: the error left is of order step^2.
      const double em = step * (1.0 + step * (0.5 + step * (1.0 / 6.0)));  // expm1(step)
      const double dlam = lam * lc * em / (1.0 + lam * em);
      const double d2f = second_derivative(lam, lc, e);
      lam += dlam;
      lc -= dlam;
      e.f += dlam * (e.df + 0.5 * dlam * d2f);
      e.x -= dlam * e.w;
      best_f = std::max(best_f, e.f);
      status = Pw85Status::ok;
      break;
    }
    if (t < 0.0) t = lam / lc;  // the warm start's t, now needed
    if (e.df > 0.0)
      t_lo = t;
    else
      t_hi = t;
    if (t_hi <= t_lo * (1.0 + tol_u)) {
      status = Pw85Status::ok;  // bracket at the resolution the data allow
      break;
    }
    // Far from the maximiser ell' can be close to 0 and a Newton step in u
    // huge (e.g. +584 for crossed needles, landing at 1 - lambda ~ 1e-254);
    // such steps are cut to kMaxStep: the step keeps its sign, so it still
    // moves towards the maximiser, and the bracket catches an overshoot.
    constexpr double kMaxStep = 4.0;
    double next = inf;
    if (std::abs(step) <= 0.5 * last_step)
      next = std::abs(step) <= kMaxStep ? t * exp_step(step) : t * (step > 0.0 ? e4 : 1.0 / e4);
    if (next > t_lo && next < t_hi) {
      t = next;
      last_step = std::abs(step);
    } else {
      // Bisection in u: u_hi - max(4, |u_hi|), u_lo + max(4, |u_lo|) while
      // one side is open, the midpoint otherwise.
      if (t_lo == 0.0)
        t = t_hi > e4 ? 1.0 : (t_hi < 1.0 / e4 ? t_hi * t_hi : t_hi / e4);
      else if (t_hi == inf)
        t = t_lo < 1.0 / e4 ? 1.0 : (t_lo > e4 ? std::min(t_lo * t_lo, 1e300) : t_lo * e4);
      else
        t = std::sqrt(t_lo) * std::sqrt(t_hi);
      last_step = inf;
    }
  }

  res.status = status;
  res.iterations = it;
  res.lambda = lam;
  res.mu2 = status == Pw85Status::ok ? e.f : best_f;
  if (shift_m != 0) res.mu2 = std::ldexp(res.mu2, -2 * shift_m);
  if (status == Pw85Status::not_converged && it == 1 && best_f == 0.0) return res;
  const double xn = e.x.norm();
  if (xn > 0.0 && std::isfinite(xn)) res.normal = e.x * (1.0 / xn);
  res.x0_rel = mul(q1, e.x) * lc;
  if (shift_r != 0) {
    // x0 - c1 = (1-l) Q1 Q^{-1} r has degree 0 in Q and 1 in r.
    for (int i = 0; i < 3; ++i) res.x0_rel[i] = std::ldexp(res.x0_rel[i], -shift_r);
  }
  return res;
}

}  // namespace grains::contact
