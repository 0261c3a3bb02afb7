#pragma once
// The arithmetic of PW85 (one evaluation of f and its Newton step, the
// safeguarded Newton iteration) and of the contact geometry taken from its
// solution, written once for T = double (pw85.cpp, ellipsoid_contact.cpp: one
// pair) and T = Lanes (pw85_lanes.cpp: kLanes pairs in lockstep, the DEM's
// batched pair stage). See pw85.hpp for the problem, docs/pw85.md for the
// method and ellipsoid_contact.hpp for the geometry.
//
// Internal to contact/ellipsoid; vectors are plain T[3], forms packed T[6].
#include <cmath>
#include <limits>

#include "contact/ellipsoid/lanes.hpp"

namespace grains::contact {
inline namespace GRAINS_LANES_ISA {
namespace pw85_kernel {

// Q = L D L^T of a packed symmetric 3x3 matrix (L unit lower triangular);
// the reciprocal pivots are kept so that the solves need no division.
template <class T>
struct Ldl {
  T i0, i1, i2, l10, l20, l21;  // 1/d0, 1/d1, 1/d2, L
};

// True (per lane) when all three pivots are positive and finite; the factors
// are computed either way (no branch), and are meaningless where false.
template <class T>
GRAINS_INLINE MaskOf<T> factor(const T* q, Ldl<T>& f) {
  const T d0 = q[0];
  f.i0 = 1.0 / d0;
  f.l10 = q[1] * f.i0;
  f.l20 = q[2] * f.i0;
  const T d1 = q[3] - f.l10 * q[1];
  f.i1 = 1.0 / d1;
  const T e = q[4] - f.l20 * q[1];  // = d1 * l21
  f.l21 = e * f.i1;
  const T d2 = q[5] - f.l20 * q[2] - f.l21 * e;
  f.i2 = 1.0 / d2;
  return (d0 > 0.0) & (d1 > 0.0) & (d2 > 0.0) & (d2 < std::numeric_limits<double>::infinity());
}

// x = Q^{-1} b; also b^T Q^{-1} b = sum y_i^2 / d_i (>= 0 by construction).
template <class T>
GRAINS_INLINE void solve(const Ldl<T>& f, const T* b, T* x, T& bqb) {
  const T y0 = b[0];
  const T y1 = b[1] - f.l10 * y0;
  const T y2 = b[2] - f.l20 * y0 - f.l21 * y1;
  const T z0 = y0 * f.i0, z1 = y1 * f.i1, z2 = y2 * f.i2;
  bqb = y0 * z0 + y1 * z1 + y2 * z2;
  x[2] = z2;
  x[1] = z1 - f.l21 * x[2];
  x[0] = z0 - f.l10 * x[1] - f.l20 * x[2];
}

template <class T>
GRAINS_INLINE void mul(const T* q, const T* v, T* out) {
  out[0] = q[0] * v[0] + q[1] * v[1] + q[2] * v[2];
  out[1] = q[1] * v[0] + q[3] * v[1] + q[4] * v[2];
  out[2] = q[2] * v[0] + q[4] * v[1] + q[5] * v[2];
}

template <class T>
GRAINS_INLINE T dot(const T* a, const T* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Everything one evaluation at lambda yields. With x = Q(l)^{-1} r,
// a = x^T Q1 x, b = x^T Q2 x, the two terms of the envelope identity
// (seed 000, eq. 13) are A1 = (1-l)^2 a and A2 = l^2 b, f = l A1 + (1-l) A2
// and f' = A1 - A2.
template <class T>
struct Eval {
  T f, df;       // f, f' with respect to lambda
  T step;        // Newton step -ell/ell' in u = log(l/(1-l)), ell = log(A1/A2)
                 // (+inf when ell' >= 0 or not finite: bisect instead)
  T g, t, a, b;  // r^T x, v^T Q^{-1} v with v = (Q2-Q1) x, a, b: for f''
  T x[3];        // Q(lambda)^{-1} r
  T w[3];        // Q(lambda)^{-1} (Q2 - Q1) x  (so dx/dlambda = -w)
};

// The Newton step where the fast formula of evaluate() does not apply: far
// from the root (|z| >= 0.1, a logarithm) or degenerate magnitudes (a or b
// zero, products out of range).
inline double slow_step(double a, double b, double a1, double a2, double df, double d) {
  if (a > 0.0 && b > 0.0 && d < 0.0) {
    const double abs_inv = a * b / d;  // = 1 / ell'
    if (std::isfinite(abs_inv) && abs_inv != 0.0) return -std::log(a1 / a2) * abs_inv;
  }
  const double iab = 1.0 / (a * b);
  double ell = df > 0.0 ? 1.0 : -1.0;
  if (a > 0.0 && b > 0.0) {
    // log(A1/A2) = 2 atanh(z), z = (A1 - A2)/(A1 + A2), by its series near the root.
    const double z = df / (a1 + a2), z2 = z * z;
    ell = z2 < 1e-2 ? 2.0 * z * (1.0 + z2 * (1.0 / 3.0 + z2 * (0.2 + z2 * (1.0 / 7.0 + z2 * (1.0 / 9.0)))))
                    : std::log(a1 / a2);
  }
  const double dell = -2.0 + (d + 2.0 * a * b) * iab;
  return dell < 0.0 ? -ell / dell : std::numeric_limits<double>::infinity();
}

// One evaluation at (lam, lc = 1 - lam; both passed so that each keeps full
// relative precision near either end). False (per lane) when Q(lambda) is
// numerically singular; the other fields are then meaningless.
template <class T>
GRAINS_INLINE MaskOf<T> evaluate(const T& lam, const T& lc, const T* r, const T* q1, const T* q2, Eval<T>& e) {
  T q[6];
  for (int i = 0; i < 6; ++i) q[i] = lc * q1[i] + lam * q2[i];
  Ldl<T> fac;
  const auto ok = factor(q, fac);
  solve(fac, r, e.x, e.g);
  T q1x[3], q2x[3];
  mul(q1, e.x, q1x);
  mul(q2, e.x, q2x);
  const T a = dot(e.x, q1x), b = dot(e.x, q2x);
  e.a = a;
  e.b = b;
  const T ll = lam * lc;
  e.f = ll * e.g;
  const T a1 = lc * lc * a, a2 = lam * lam * b;
  e.df = a1 - a2;
  const T v[3] = {q2x[0] - q1x[0], q2x[1] - q1x[1], q2x[2] - q1x[2]};
  solve(fac, v, e.w, e.t);
  // ell' = D / (a b) with D = 2 l (1-l) (a (Q2 x).w - b (Q1 x).w) - 2 a b, and
  // near the root ell = 2 atanh(z), z = f'/(A1 + A2): one division gives both
  // z and the step -ell/ell' = -ell a b (A1 + A2) / ((A1 + A2) D). The series
  // of atanh (relative error < 1e-11 for |z| < 0.1) replaces the logarithm;
  // it only perturbs the step by that fraction of itself.
  const T sum = a1 + a2;
  const T d = 2.0 * ll * (dot(q2x, e.w) * a - dot(q1x, e.w) * b) - 2.0 * a * b;
  const T inv = 1.0 / (sum * d);
  const T abs_inv = a * b * sum * inv;  // = 1 / ell'
  const T z = e.df * d * inv;
  const T z2 = z * z;
  e.step = -2.0 * z * (1.0 + z2 * (1.0 / 3.0 + z2 * (0.2 + z2 * (1.0 / 7.0 + z2 * (1.0 / 9.0))))) * abs_inv;
  const MaskOf<T> fast = (a > 0.0) & (b > 0.0) & (d < 0.0) & (z2 < 1e-2) & (abs_inv != 0.0) &
                    (abs_inv < std::numeric_limits<double>::infinity()) &
                    (-abs_inv < std::numeric_limits<double>::infinity());
  if (!all_of(fast))
    for (int l = 0; l < lane_count<T>; ++l)
      if (!lane(fast, l))
        set_lane(e.step, l, slow_step(get_lane(a, l), get_lane(b, l), get_lane(a1, l), get_lane(a2, l), get_lane(e.df, l), get_lane(d, l)));
  return ok;
}

// f''(lambda) from the quantities of an evaluation.
inline double second_derivative(double lam, double lc, double g, double t, double a, double b) {
  return -2.0 * g - 2.0 * (lc - lam) * (b - a) + 2.0 * lam * lc * t;
}

// The safeguarded Newton iteration on ell(u) = log(A1/A2) = 0 in the logit
// variable u = log(lambda/(1-lambda)), one pair (one lane) at a time: for two
// spheres ell is linear in u (one step), and maximisers hugging lambda = 0 or
// 1 (elongated bodies) stay well scaled. ell has the sign of f', so
// [u_lo, u_hi] always brackets the maximiser (f concave, f'(0) > 0 > f'(1));
// a step leaving it, or one that fails to halve the previous one, is replaced
// by bisection. The iterate is carried as t = e^u = lambda/(1-lambda)
// (lambda = t/(1+t), 1-lambda = 1/(1+t), both to full relative precision),
// so that a step multiplies t by e^du and bisection in u is a geometric mean
// in t: no log or exp near convergence.
struct Newton {
  double t = -1.0;  // < 0: not formed yet (a warm start evaluates at its guess)
  double lam = 0.5, lc = 0.5;
  double t_lo = 0.0, t_hi = std::numeric_limits<double>::infinity();
  double last_step = std::numeric_limits<double>::infinity();
  double best_f = 0.0;  // f >= 0 everywhere: always a valid lower bound
  int it = 0;

  // Warm start from lambda in (0, 1): evaluated at the guess itself; t is
  // formed only if the iteration goes on (two divisions fewer on a persistent
  // contact's path). Cold start: the exact answer for two spheres of radii
  // h1, h2 (the support radii of the bodies along r), t = h1/h2, from
  // rq1r = r^T Q1 r and rq2r = r^T Q2 r.
  void start(double lambda_guess, double rq1r, double rq2r) {
    if (lambda_guess > 0.0 && lambda_guess < 1.0) {
      lam = lambda_guess;
      lc = 1.0 - lambda_guess;
    } else {
      t = std::sqrt(rq1r / rq2r);
      lc = 1.0 / (1.0 + t);
      lam = t * lc;
    }
  }

  enum Verdict { again, converged, final_step, separated };

  // After an evaluation at (lam, lc) with value f, slope df and Newton step:
  // `again` (lam, lc now hold the next point), `converged` (at lam), or
  // `final_step`: the step was below tol_u and is taken from the derivatives
  // at hand instead of another factorisation (error of order step^2); lam
  // and lc are updated and dlam is the change, for the caller to move f and
  // x (f += dlam (df + dlam f''/2), x -= dlam w). `separated`: f exceeded
  // separated_above (pass +inf not to stop).
  Verdict next(double f, double df, double step, double tol_u, double separated_above, double& dlam) {
    ++it;
    best_f = std::max(best_f, f);
    if (f > separated_above) return separated;
    if (df == 0.0) return converged;
    if (std::abs(step) <= tol_u) {
      const double em = step * (1.0 + step * (0.5 + step * (1.0 / 6.0)));  // expm1(step)
      dlam = lam * lc * em / (1.0 + lam * em);
      lam += dlam;
      lc -= dlam;
      return final_step;
    }
    if (t < 0.0) t = lam / lc;  // the warm start's t, now needed
    if (df > 0.0)
      t_lo = t;
    else
      t_hi = t;
    if (t_hi <= t_lo * (1.0 + tol_u)) return converged;  // bracket at the resolution the data allow
    // Far from the maximiser ell' can be close to 0 and a Newton step in u
    // huge (e.g. +584 for crossed needles, landing at 1 - lambda ~ 1e-254);
    // such steps are cut to kMaxStep: the step keeps its sign, so it still
    // moves towards the maximiser, and the bracket catches an overshoot.
    constexpr double kMaxStep = 4.0;
    constexpr double e4 = 54.598150033144236;  // e^4
    constexpr double inf = std::numeric_limits<double>::infinity();
    double nt = inf;
    if (std::abs(step) <= 0.5 * last_step)
      nt = std::abs(step) <= kMaxStep ? t * exp_step(step) : t * (step > 0.0 ? e4 : 1.0 / e4);
    if (nt > t_lo && nt < t_hi) {
      t = nt;
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
    lc = 1.0 / (1.0 + t);
    lam = t * lc;
    return again;
  }

  // exp(s) for the Newton update of t; the Taylor form for small steps
  // (relative error < 3e-9 for |s| < 0.05: the new point moves by that much
  // in u, far less than the Newton error it leaves).
  static double exp_step(double s) {
    if (std::abs(s) < 0.05) return 1.0 + s * (1.0 + s * (0.5 + s * (1.0 / 6.0 + s * (1.0 / 24.0))));
    return std::exp(s);
  }
};

// ---- Contact geometry from the PW85 normal (ellipsoid_contact.hpp) --------

// Orthonormal t1, t2 with t1 x t2 = n (n unit). Branch-free construction
// (Duff et al., "Building an orthonormal basis, revisited", JCGT 2017).
template <class T>
GRAINS_INLINE void tangent_basis(const T* n, T* t1, T* t2) {
  const T s = sign_(n[2]);
  const T a = -1.0 / (s + n[2]);
  const T b = n[0] * n[1] * a;
  t1[0] = 1.0 + s * n[0] * n[0] * a;
  t1[1] = s * b;
  t1[2] = -s * n[0];
  t2[0] = b;
  t2[1] = s + n[1] * n[1] * a;
  t2[2] = -n[1];
}

// h^2 (T^T Q T) - v v^T, v = T^T Q n, T = [t1 t2]: the 2x2 matrix whose
// inverse times h^3 is the surface's curvature tensor at its support point
// of normal n (surface_curvature.hpp), as {m11, m12, m22}; qn = Q n,
// h2 = n^T Q n.
template <class T>
GRAINS_INLINE void scaled_tangent_form(const T* q, const T* qn, const T& h2, const T* t1, const T* t2, T* m) {
  T qt1[3], qt2[3];
  mul(q, t1, qt1);
  mul(q, t2, qt2);
  const T v1 = dot(t1, qn), v2 = dot(t2, qn);
  m[0] = h2 * dot(t1, qt1) - v1 * v1;
  m[1] = h2 * dot(t1, qt2) - v1 * v2;
  m[2] = h2 * dot(t2, qt2) - v2 * v2;
}

// R* = 1/sqrt(det(K_i + K_j)) of two ellipsoids at their support points of
// normals +n and -n, with one division and one square root (the derivation
// is at surface_curvature.hpp's hertz_radius_of_pair).
template <class T>
GRAINS_INLINE T hertz_radius_of_pair(const T* qi, const T* qin, const T& hi2, const T& hi, const T* qj, const T* qjn,
                              const T& hj2, const T& hj, const T* t1, const T* t2) {
  T mi[3], mj[3];
  scaled_tangent_form(qi, qin, hi2, t1, t2, mi);
  scaled_tangent_form(qj, qjn, hj2, t1, t2, mj);
  const T di = mi[0] * mi[2] - mi[1] * mi[1], dj = mj[0] * mj[2] - mj[1] * mj[1];
  const T c = mi[2] * mj[0] + mi[0] * mj[2] - 2.0 * mi[1] * mj[1];
  const T h3i = hi2 * hi, h3j = hj2 * hj;
  return sqrt_(di * dj / (h3i * h3i * dj + h3j * h3j * di + h3i * h3j * c));
}

// Geometry of bodies i = (ci, qi) and j = (cj, qj) touching along the unit
// PW85 normal n (from i towards j): support points p_i = c_i + Q_i n / h_i,
// p_j = c_j - Q_j n / h_j, overlap h_i + h_j - (c_j - c_i).n, contact point
// their midpoint, normal -n (from j towards i), and R*.
template <class T>
struct PairGeometry {
  T normal[3];
  T overlap;
  T point[3];
  T radius;
};

template <class T>
GRAINS_INLINE void pair_geometry(const T* ci, const T* qi, const T* cj, const T* qj, const T* n, PairGeometry<T>& g) {
  T qin[3], qjn[3];
  mul(qi, n, qin);
  mul(qj, n, qjn);
  const T hi2 = dot(n, qin), hj2 = dot(n, qjn);
  const T hi = sqrt_(hi2), hj = sqrt_(hj2);
  const T ihi = 1.0 / hi, ihj = 1.0 / hj;
  for (int k = 0; k < 3; ++k) {
    g.normal[k] = -n[k];
    g.point[k] = 0.5 * ((ci[k] + qin[k] * ihi) + (cj[k] - qjn[k] * ihj));
  }
  const T rn = (cj[0] - ci[0]) * n[0] + (cj[1] - ci[1]) * n[1] + (cj[2] - ci[2]) * n[2];
  g.overlap = hi + hj - rn;
  T t1[3], t2[3];
  tangent_basis(n, t1, t2);
  g.radius = hertz_radius_of_pair(qi, qin, hi2, hi, qj, qjn, hj2, hj, t1, t2);
}

}  // namespace pw85_kernel
}  // namespace GRAINS_LANES_ISA
}  // namespace grains::contact
