// PW85 contact function: safeguarded Newton on f'(lambda) = 0. See pw85.hpp
// for the problem and docs/pw85.md for the method and its measured accuracy.
#include "contact/ellipsoid/pw85.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/ellipsoid/pw85_kernel.hpp"

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

using namespace pw85_kernel;

bool all_finite(const double* p, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(p[i])) return false;
  return true;
}

inline Vector3d mul(const double* q, const Vector3d& v) {
  Vector3d out;
  pw85_kernel::mul(q, v.data(), out.data());
  return out;
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
  Ldl<double> f;
  if (!all_finite(q.data(), 6)) return false;
  return factor(q.data(), f);
}

double pw85_f(double lambda, const Vector3d& r, const SymMat3& q1, const SymMat3& q2) {
  Eval<double> e;
  if (!evaluate(lambda, 1.0 - lambda, r.data(), q1.data(), q2.data(), e))
    return std::numeric_limits<double>::quiet_NaN();
  return e.f;
}

bool pw85_separated_at(double lambda, const Vector3d& r, const SymMat3& q1, const SymMat3& q2) {
  const double lc = 1.0 - lambda;
  double q[6];
  for (int i = 0; i < 6; ++i) q[i] = lc * q1[i] + lambda * q2[i];
  Ldl<double> fac;
  if (!factor(q, fac)) return false;
  double g, x[3];
  solve(fac, r.data(), x, g);
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
    Ldl<double> f1, f2;
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

  // Safeguarded Newton in u = log(lambda/(1-lambda)) (pw85_kernel::Newton).
  Newton nw;
  const bool cold = !(opt.lambda_guess > 0.0 && opt.lambda_guess < 1.0);
  nw.start(opt.lambda_guess, cold ? r.dot(mul(q1, r)) : 1.0, cold ? r.dot(mul(q2, r)) : 1.0);
  const double stop_above = opt.stop_if_separated ? separated_above : std::numeric_limits<double>::infinity();
  Eval<double> e;
  Pw85Status status = Pw85Status::not_converged;
  while (nw.it < opt.max_iterations) {
    if (!evaluate(nw.lam, nw.lc, r.data(), q1, q2, e)) {
      // Q(lambda) is a convex combination of SPD matrices: this only happens
      // for pairs too ill-conditioned for double precision.
      ++nw.it;
      break;
    }
    double dlam = 0.0;
    const double lam0 = nw.lam, lc0 = nw.lc;
    const auto verdict = nw.next(e.f, e.df, e.step, opt.tolerance, stop_above, dlam);
    if (verdict == Newton::again) continue;
    if (verdict == Newton::separated) {
      status = Pw85Status::separated;
      break;
    }
    if (verdict == Newton::final_step) {
      e.f += dlam * (e.df + 0.5 * dlam * second_derivative(lam0, lc0, e.g, e.t, e.a, e.b));
      for (int i = 0; i < 3; ++i) e.x[i] -= dlam * e.w[i];
      nw.best_f = std::max(nw.best_f, e.f);
    }
    status = Pw85Status::ok;
    break;
  }
  const double lam = nw.lam, lc = nw.lc, best_f = nw.best_f;
  const int it = nw.it;

  res.status = status;
  res.iterations = it;
  res.lambda = lam;
  res.mu2 = status == Pw85Status::ok ? e.f : best_f;
  if (shift_m != 0) res.mu2 = std::ldexp(res.mu2, -2 * shift_m);
  if (status == Pw85Status::not_converged && it == 1 && best_f == 0.0) return res;
  const Vector3d x(e.x[0], e.x[1], e.x[2]);
  const double xn = x.norm();
  if (xn > 0.0 && std::isfinite(xn)) res.normal = x * (1.0 / xn);
  res.x0_rel = mul(q1, x) * lc;
  if (shift_r != 0) {
    // x0 - c1 = (1-l) Q1 Q^{-1} r has degree 0 in Q and 1 in r.
    for (int i = 0; i < 3; ++i) res.x0_rel[i] = std::ldexp(res.x0_rel[i], -shift_r);
  }
  return res;
}

}  // namespace grains::contact
