// PW85 and contact geometry of many pairs in lockstep: see pw85_lanes.hpp.
#include "contact/ellipsoid/pw85_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/ellipsoid/pw85_kernel.hpp"

namespace grains::contact {

using namespace pw85_kernel;

namespace {

// The unit normal from x = Q(lambda)^{-1} r as pw85_contact forms it:
// x / |x|, or (0, 0, 1) where |x| is zero or not finite.
template <class T>
inline void unit_normal(const T* x, T* n) {
  const T xn = sqrt_(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  const auto good = (xn > 0.0) & (xn < std::numeric_limits<double>::infinity());
  const T inv = 1.0 / xn;
  n[0] = select(good, x[0] * inv, T(0.0));
  n[1] = select(good, x[1] * inv, T(0.0));
  n[2] = select(good, x[2] * inv, T(1.0));
}

}  // namespace

void pw85_contact_lanes(const Pw85LaneJob* jobs, std::size_t count, Pw85LaneResult* out, double tolerance,
                        bool stop_if_separated, int max_iterations) {
  constexpr int W = kLanes;
  const double stop_above = stop_if_separated ? 1.0 : std::numeric_limits<double>::infinity();
  // Lane state. An idle lane keeps computing on its last (or a harmless
  // placeholder) pair; its results are ignored.
  Lanes lam(0.5), lc(0.5), r[3], q1[6], q2[6];
  for (int k = 0; k < 3; ++k) r[k] = Lanes(k == 0 ? 1.0 : 0.0);
  for (int k = 0; k < 6; ++k) q1[k] = q2[k] = Lanes(k == 0 || k == 3 || k == 5 ? 1.0 : 0.0);
  Newton nw[W];
  std::size_t job[W];
  bool active[W] = {};
  std::size_t next = 0;
  Eval<Lanes> e;
  for (;;) {
    int busy = 0;
    for (int l = 0; l < W; ++l) {
      while (!active[l] && next < count) {
        const Pw85LaneJob& jb = jobs[next];
        const std::size_t id = next++;
        if (jb.r[0] == 0.0 && jb.r[1] == 0.0 && jb.r[2] == 0.0) {  // coincident centres
          out[id] = {Pw85Status::ok, 0.0, 0.5, {0.0, 0.0, 0.0}};
          continue;
        }
        for (int k = 0; k < 3; ++k) set_lane(r[k], l, jb.r[k]);
        for (int k = 0; k < 6; ++k) {
          set_lane(q1[k], l, jb.qi[k]);
          set_lane(q2[k], l, jb.qj[k]);
        }
        nw[l] = Newton{};
        double rq1r = 0.0, rq2r = 0.0;
        if (!(jb.lambda_guess > 0.0 && jb.lambda_guess < 1.0)) {
          double t1[3], t2[3];
          mul(jb.qi, jb.r, t1);
          mul(jb.qj, jb.r, t2);
          rq1r = dot(jb.r, t1);
          rq2r = dot(jb.r, t2);
        }
        nw[l].start(jb.lambda_guess, rq1r, rq2r);
        set_lane(lam, l, nw[l].lam);
        set_lane(lc, l, nw[l].lc);
        job[l] = id;
        active[l] = true;
      }
      busy += active[l];
    }
    if (busy == 0) break;
    const LaneMask ok = evaluate(lam, lc, r, q1, q2, e);
    for (int l = 0; l < W; ++l) {
      if (!active[l]) continue;
      Pw85LaneResult& o = out[job[l]];
      Newton& s = nw[l];
      if (!lane(ok, l)) {  // Q(lambda) did not factor: too ill-conditioned
        ++s.it;
        o = {Pw85Status::not_converged, s.best_f, s.lam, {0.0, 0.0, 1.0}};
        active[l] = false;
        continue;
      }
      const double lam0 = s.lam, lc0 = s.lc, f = get_lane(e.f, l), df = get_lane(e.df, l);
      double dlam = 0.0;
      const auto verdict = s.next(f, df, get_lane(e.step, l), tolerance, stop_above, dlam);
      if (verdict == Newton::again) {
        if (s.it < max_iterations) {
          set_lane(lam, l, s.lam);
          set_lane(lc, l, s.lc);
          continue;
        }
        o = {Pw85Status::not_converged, s.best_f, s.lam, {get_lane(e.x[0], l), get_lane(e.x[1], l), get_lane(e.x[2], l)}};
      } else if (verdict == Newton::separated) {
        o = {Pw85Status::separated, s.best_f, s.lam, {get_lane(e.x[0], l), get_lane(e.x[1], l), get_lane(e.x[2], l)}};
      } else {
        o.status = Pw85Status::ok;
        o.lambda = s.lam;
        o.mu2 = f;
        for (int k = 0; k < 3; ++k) o.x[k] = get_lane(e.x[k], l);
        if (verdict == Newton::final_step) {
          o.mu2 += dlam * (df + 0.5 * dlam *
                                    second_derivative(lam0, lc0, get_lane(e.g, l), get_lane(e.t, l), get_lane(e.a, l), get_lane(e.b, l)));
          for (int k = 0; k < 3; ++k) o.x[k] -= dlam * get_lane(e.w[k], l);
        }
      }
      active[l] = false;
    }
  }
}

void contact_geometry_lanes(const PairGeometryJob* jobs, std::size_t count, ContactGeometry* out) {
  constexpr int W = kLanes;
  for (std::size_t first = 0; first < count; first += W) {
    // Gathered lane by lane into plain arrays, then loaded as packs.
    double buf[21][kLanes];  // ci, cj, x (3 each), qi, qj (6 each)
    for (int l = 0; l < W; ++l) {
      // The last group is padded with copies of its last pair.
      const PairGeometryJob& jb = jobs[std::min(first + l, count - 1)];
      for (int k = 0; k < 3; ++k) {
        buf[k][l] = jb.ci[k];
        buf[3 + k][l] = jb.cj[k];
        buf[6 + k][l] = jb.x[k];
      }
      for (int k = 0; k < 6; ++k) {
        buf[9 + k][l] = jb.qi[k];
        buf[15 + k][l] = jb.qj[k];
      }
    }
    Lanes v[21];
    for (int k = 0; k < 21; ++k) v[k] = load_lanes(buf[k]);
    const Lanes *ci = v, *cj = v + 3, *x = v + 6, *qi = v + 9, *qj = v + 15;
    Lanes n[3];
    unit_normal(x, n);
    PairGeometry<Lanes> g;
    pair_geometry(ci, qi, cj, qj, n, g);
    for (int l = 0; l < W && first + l < count; ++l) {
      ContactGeometry& o = out[first + l];
      o.normal = {get_lane(g.normal[0], l), get_lane(g.normal[1], l), get_lane(g.normal[2], l)};
      o.overlap = get_lane(g.overlap, l);
      o.point = {get_lane(g.point[0], l), get_lane(g.point[1], l), get_lane(g.point[2], l)};
      o.radius = get_lane(g.radius, l);
    }
  }
}

}  // namespace grains::contact
