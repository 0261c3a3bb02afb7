// PW85 and contact geometry of many pairs in lockstep: see pw85_lanes.hpp.
#include "contact/ellipsoid/pw85_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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

namespace {

// A pair whose first evaluation did not settle it, with its iteration state.
struct Continuing {
  std::size_t job;
  Newton newton;
};

// Evaluations of the pairs job[0..kLanes) (a lane may repeat the group's
// last pair: padding, active[l] false) from their states nw[l]. With
// `until_done` the group iterates until every lane is settled; otherwise
// after one evaluation the unsettled lanes go to `later` with their state.
void run_group(const Pw85LaneJob* jobs, const std::size_t* job, Newton* nw, bool* active, Pw85LaneResult* out,
               double tolerance, double stop_above, int max_iterations, bool until_done,
               std::vector<Continuing>& later) {
  constexpr int W = kLanes;
  Lanes r[3], q1[6], q2[6];
  for (int k = 0; k < 3; ++k) r[k] = gather_lanes([&](int l) { return jobs[job[l]].r[k]; });
  for (int k = 0; k < 6; ++k) {
    q1[k] = gather_lanes([&](int l) { return jobs[job[l]].qi[k]; });
    q2[k] = gather_lanes([&](int l) { return jobs[job[l]].qj[k]; });
  }
  Eval<Lanes> e;
  for (;;) {
    const Lanes lam = gather_lanes([&](int l) { return nw[l].lam; });
    const Lanes lc = gather_lanes([&](int l) { return nw[l].lc; });
    const LaneMask ok = evaluate(lam, lc, r, q1, q2, e);
    bool busy = false;
    for (int l = 0; l < W; ++l) {
      if (!active[l]) continue;
      Pw85LaneResult& o = out[job[l]];
      Newton& s = nw[l];
      active[l] = false;
      if (!lane(ok, l)) {  // Q(lambda) did not factor: too ill-conditioned
        ++s.it;
        o = {Pw85Status::not_converged, s.best_f, s.lam, {0.0, 0.0, 1.0}};
        continue;
      }
      const double lam0 = s.lam, lc0 = s.lc, f = get_lane(e.f, l), df = get_lane(e.df, l);
      double dlam = 0.0;
      const auto verdict = s.next(f, df, get_lane(e.step, l), tolerance, stop_above, dlam);
      const double x[3] = {get_lane(e.x[0], l), get_lane(e.x[1], l), get_lane(e.x[2], l)};
      if (verdict == Newton::again) {
        if (s.it >= max_iterations) {
          o = {Pw85Status::not_converged, s.best_f, s.lam, {x[0], x[1], x[2]}};
        } else if (until_done) {
          active[l] = busy = true;
        } else {
          later.push_back({job[l], s});
        }
      } else if (verdict == Newton::separated) {
        o = {Pw85Status::separated, s.best_f, s.lam, {x[0], x[1], x[2]}};
      } else {
        o = {Pw85Status::ok, f, s.lam, {x[0], x[1], x[2]}};
        if (verdict == Newton::final_step) {
          o.mu2 += dlam * (df + 0.5 * dlam *
                                    second_derivative(lam0, lc0, get_lane(e.g, l), get_lane(e.t, l),
                                                      get_lane(e.a, l), get_lane(e.b, l)));
          for (int k = 0; k < 3; ++k) o.x[k] -= dlam * get_lane(e.w[k], l);
        }
      }
    }
    if (!busy) return;
  }
}

}  // namespace

void pw85_contact_lanes(const Pw85LaneJob* jobs, std::size_t count, Pw85LaneResult* out, double tolerance,
                        bool stop_if_separated, int max_iterations) {
  constexpr int W = kLanes;
  const double stop_above = stop_if_separated ? 1.0 : std::numeric_limits<double>::infinity();
  // Most pairs are settled by their first evaluation (a persistent contact
  // from its warm start, a pair apart by f > 1 at its previous lambda): all
  // pairs get one evaluation in groups of kLanes consecutive jobs, and the
  // few that need more iterate afterwards in groups of their own, so that
  // lanes seldom idle.
  thread_local std::vector<Continuing> later;
  later.clear();
  std::size_t job[W];
  Newton nw[W];
  bool active[W];
  for (std::size_t first = 0; first < count; first += W) {
    for (int l = 0; l < W; ++l) {
      job[l] = std::min(first + l, count - 1);
      active[l] = first + l < count;
      const Pw85LaneJob& jb = jobs[job[l]];
      nw[l] = Newton{};
      if (active[l] && jb.r[0] == 0.0 && jb.r[1] == 0.0 && jb.r[2] == 0.0) {  // coincident centres: mu2 = 0
        out[job[l]] = {Pw85Status::ok, 0.0, 0.5, {0.0, 0.0, 0.0}};
        active[l] = false;
      }
      double rq1r = 1.0, rq2r = 1.0;
      if (active[l] && !(jb.lambda_guess > 0.0 && jb.lambda_guess < 1.0)) {
        double t1[3], t2[3];
        mul(jb.qi, jb.r, t1);
        mul(jb.qj, jb.r, t2);
        rq1r = dot(jb.r, t1);
        rq2r = dot(jb.r, t2);
      }
      nw[l].start(active[l] ? jb.lambda_guess : 0.5, rq1r, rq2r);
    }
    run_group(jobs, job, nw, active, out, tolerance, stop_above, max_iterations, false, later);
  }
  for (std::size_t first = 0; first < later.size(); first += W) {
    for (int l = 0; l < W; ++l) {
      const Continuing& c = later[std::min(first + l, later.size() - 1)];
      job[l] = c.job;
      nw[l] = c.newton;
      active[l] = first + l < later.size();
    }
    run_group(jobs, job, nw, active, out, tolerance, stop_above, max_iterations, true, later);
  }
}

void contact_geometry_lanes(const PairGeometryJob* jobs, std::size_t count, ContactGeometry* out) {
  constexpr int W = kLanes;
  for (std::size_t first = 0; first < count; first += W) {
    // The last group is padded with copies of its last pair.
    const PairGeometryJob* jb[W];
    for (int l = 0; l < W; ++l) jb[l] = &jobs[std::min(first + l, count - 1)];
    Lanes ci[3], cj[3], x[3], qi[6], qj[6];
    for (int k = 0; k < 3; ++k) {
      ci[k] = gather_lanes([&](int l) { return jb[l]->ci[k]; });
      cj[k] = gather_lanes([&](int l) { return jb[l]->cj[k]; });
      x[k] = gather_lanes([&](int l) { return jb[l]->x[k]; });
    }
    for (int k = 0; k < 6; ++k) {
      qi[k] = gather_lanes([&](int l) { return jb[l]->qi[k]; });
      qj[k] = gather_lanes([&](int l) { return jb[l]->qj[k]; });
    }
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
