// Ellipsoid-plane and ellipsoid-cylinder contacts: see ellipsoid_walls.hpp.
#include "contact/ellipsoid/ellipsoid_walls.hpp"
#include "contact/ellipsoid/illinois.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "contact/ellipsoid/point_ellipsoid.hpp"
#include "contact/ellipsoid/secular_equation.hpp"
#include "contact/ellipsoid/surface_curvature.hpp"

namespace grains::contact {

using Eigen::Vector2d;
using Eigen::Vector3d;

ContactGeometry ellipsoid_plane_contact(const Vector3d& centre, const SymMat3& q, const Vector3d& semi_axes,
                                        const Plane& wall, bool* touching) {
  const Vector3d& m = wall.normal;
  const Vector3d qm = form_times(q, m);
  const double h2 = m.dot(qm), h = std::sqrt(h2);
  ContactGeometry g;
  g.normal = m;
  g.overlap = h - (centre - wall.point).dot(m);
  const Vector3d deepest = centre - qm * (1.0 / h);
  g.point = deepest + 0.5 * g.overlap * m;
  // Against a plane K_body alone: det K = h^2 det(T^T Q^-1 T) = h^2 m^T adj(Q^-1) m
  // = h^4 / det Q (the normal cofactor; adj(Q^-1) = Q / det Q), so
  // R* = 1/sqrt(det K) = a0 a1 a2 / h^2, the Gaussian curvature radius.
  g.radius = semi_axes[0] * semi_axes[1] * semi_axes[2] / h2;
  if (touching) *touching = g.overlap > 0.0;
  return g;
}

ContactGeometry ellipsoid_plane_contact(const Ellipsoid& body, const Plane& wall, bool* touching) {
  return ellipsoid_plane_contact(body.centre, body.form(), body.semi_axes, wall, touching);
}

namespace {

// The post: closest point of the shadow ellipse (principal frame v0, v1,
// semi-axes b0 >= b1, centre cp relative to the axis) to the axis.
ContactGeometry outside_cylinder(const Ellipsoid& body, const CylinderSurface& wall, const SymMat3& q,
                                 const Vector3d& t1, const Vector3d& t2, const Vector2d& v0, const Vector2d& v1,
                                 const double (&cp)[2], const double (&b)[2], double b0sq_minus_b1sq,
                                 bool* touching) {
  // The axis seen from the ellipse centre, y = -cp; work with lengths of
  // order one (the answer is homogeneous of degree one).
  const double scale = b[0];
  const double e[2] = {1.0, b[1] / scale};
  const double y[2] = {-cp[0] / scale, -cp[1] / scale};
  // Multiplier referred to the smaller axis (secular_equation.hpp):
  // x_i = e_i^2 y_i / (s + d_i), d_i = e_i^2 - e_1^2.
  const double d[2] = {b0sq_minus_b1sq / (scale * scale), 0.0};
  const double alpha[2] = {e[0] * std::abs(y[0]), e[1] * std::abs(y[1])};
  const double s = secular_root(alpha, d);
  double x[2];
  if (s > 0.0) {
    x[0] = e[0] * e[0] * y[0] / (s + d[0]);
    x[1] = e[1] * e[1] * y[1] / s;
  } else {
    // Axis inside the ellipse on its major axis line: the closest boundary
    // points are symmetric about it; take the +v1 one.
    x[0] = d[0] > 0.0 ? e[0] * e[0] * y[0] / d[0] : 0.0;
    x[1] = e[1] * std::sqrt(std::max(0.0, 1.0 - x[0] * x[0]));
  }
  const double inside_ellipse = (y[0] / e[0]) * (y[0] / e[0]) + (y[1] / e[1]) * (y[1] / e[1]);
  const double dist = std::hypot(y[0] - x[0], y[1] - x[1]) * scale;
  const double signed_distance = inside_ellipse < 1.0 ? -dist : dist;
  // Outward normal of the ellipse at x (principal frame), lifted to 3D.
  Vector2d n2(x[0] / (e[0] * e[0]), x[1] / (e[1] * e[1]));
  n2 = (n2[0] * v0 + n2[1] * v1).normalized();
  const Vector3d n = n2[0] * t1 + n2[1] * t2;  // body's outward normal, towards the axis
  const Vector3d qn = form_times(q, n);
  const double h = std::sqrt(n.dot(qn));
  const Vector3d contact_on_body = body.centre + qn / h;
  ContactGeometry g;
  g.normal = -n;
  g.overlap = wall.radius - signed_distance;
  g.point = contact_on_body - 0.5 * g.overlap * n;
  const Vector3d& dax = wall.axis;
  const Vector3d circ = dax.cross(n);
  const Eigen::Matrix2d k_body = curvature_tensor(q, n, dax, circ);
  Eigen::Matrix2d k = k_body;
  k(1, 1) += 1.0 / wall.radius;  // convex post
  g.radius = hertz_radius(k);
  if (touching) {
    const double zc = (contact_on_body - wall.base).dot(dax);
    *touching = g.overlap > 0.0 && zc >= wall.t_min && zc <= wall.t_max;
  }
  return g;
}

}  // namespace

ContactGeometry ellipsoid_cylinder_contact(const Ellipsoid& body, const CylinderSurface& wall,
                                           bool* touching) {
  const SymMat3 q = body.form();
  const Vector3d& d = wall.axis;
  Vector3d t1, t2;
  tangent_basis(d, t1, t2);
  // Shadow ellipse in the plane normal to the axis.
  const Vector3d rel = body.centre - wall.base;
  const Vector2d c(rel.dot(t1), rel.dot(t2));
  const double a00 = t1.dot(form_times(q, t1)), a01 = t1.dot(form_times(q, t2)), a11 = t2.dot(form_times(q, t2));
  // Principal frame: b0^2 >= b1^2, eigenvector v0 at angle theta.
  const double mean = 0.5 * (a00 + a11);
  const double rad = std::hypot(0.5 * (a00 - a11), a01);
  const double b0sq = mean + rad;
  const double b1sq = (a00 * a11 - a01 * a01) / b0sq;
  const double theta = 0.5 * std::atan2(2.0 * a01, a00 - a11);
  const Vector2d v0(std::cos(theta), std::sin(theta)), v1(-v0[1], v0[0]);
  const double cp[2] = {c.dot(v0), c.dot(v1)};
  const double b[2] = {std::sqrt(b0sq), std::sqrt(b1sq)};
  if (!wall.inside) return outside_cylinder(body, wall, q, t1, t2, v0, v1, cp, b, 2.0 * rad, touching);
  // Farthest point c + z: z_i = b_i^2 cp_i / (s + d_i), d_i = b0^2 - b_i^2.
  const double dd[2] = {0.0, 2.0 * rad};
  const double alpha[2] = {b[0] * std::abs(cp[0]), b[1] * std::abs(cp[1])};
  const double s = secular_root(alpha, dd);
  double z[2];
  if (s > 0.0) {
    z[0] = b0sq * cp[0] / s;
    z[1] = b1sq * cp[1] / (s + dd[1]);
  } else {
    // Centre on the ellipse's minor axis line through the cylinder axis: the
    // farthest points are symmetric; take the one on the +v0 side.
    z[1] = dd[1] > 0.0 ? b1sq * cp[1] / dd[1] : 0.0;
    z[0] = b[0] * std::sqrt(std::max(0.0, 1.0 - (z[1] / b[1]) * (z[1] / b[1])));
  }
  const Vector2d x = c + z[0] * v0 + z[1] * v1;
  const double rho = x.norm();
  const Vector2d u2 = rho > 0.0 ? Vector2d(x / rho) : Vector2d(v0);
  const Vector3d u = u2[0] * t1 + u2[1] * t2;  // outward radial direction
  const Vector3d qu = form_times(q, u);
  const double h = std::sqrt(u.dot(qu));
  const Vector3d contact_on_body = body.centre + qu / h;
  ContactGeometry g;
  g.normal = -u;
  g.overlap = rho - wall.radius;
  g.point = contact_on_body - 0.5 * g.overlap * u;
  // Curvatures in the tangent plane at the contact: the axis d and the
  // circumferential direction e = d x u (both orthogonal to u).
  const Vector3d e = d.cross(u);
  const Eigen::Matrix2d k_body = curvature_tensor(q, u, d, e);
  Eigen::Matrix2d k = k_body;
  k(1, 1) -= 1.0 / wall.radius;  // concave wall
  // A body as curved as the wall (conforming contact) would give R* = inf;
  // floor the relative curvature at 1e-3 of the body's own.
  g.radius = hertz_radius(k, 1e-3 * std::min(k_body(0, 0), k_body(1, 1)));
  if (touching) {
    const double zc = (contact_on_body - wall.base).dot(d);
    *touching = g.overlap > 0.0 && zc >= wall.t_min && zc <= wall.t_max;
  }
  return g;
}

namespace {

// A rim circle q(t) = c + rho (cos t e1 + sin t e2) and the body's quadratic
// F(t) = (q - x)^T Q^-1 (q - x) along it,
//   F = k0 + k1 cos t + k2 sin t + k3 cos^2 t + k4 sin t cos t + k5 sin^2 t.
struct RimCircle {
  Vector3d c, e1, e2;
  double rho = 0;
  double k[6] = {};

  Vector3d at(double t) const { return c + rho * (std::cos(t) * e1 + std::sin(t) * e2); }
  Vector3d tangent(double t) const { return rho * (-std::sin(t) * e1 + std::cos(t) * e2); }
  double f(double t) const {
    const double co = std::cos(t), si = std::sin(t);
    return k[0] + k[1] * co + k[2] * si + k[3] * co * co + k[4] * si * co + k[5] * si * si;
  }
  double df(double t) const {
    const double co = std::cos(t), si = std::sin(t);
    return -k[1] * si + k[2] * co + 2.0 * (k[5] - k[3]) * si * co + k[4] * (co * co - si * si);
  }
  double d2f(double t) const {
    const double co = std::cos(t), si = std::sin(t);
    return -k[1] * co - k[2] * si + 2.0 * (k[5] - k[3]) * (co * co - si * si) - 4.0 * k[4] * si * co;
  }
};

struct RimMax {
  Vector3d q;
  ClosestPoint cp;
  double depth() const { return -cp.signed_distance; }
};

// Local maxima of the depth along the rim with positive depth (at most two).
int rim_maxima(const Ellipsoid& body, const RimCircle& rim, RimMax out[2]) {
  constexpr int N = 32;
  constexpr double h = 2.0 * std::numbers::pi / N;
  double fs[N];
  bool all_inside = true;
  for (int j = 0; j < N; ++j) {
    fs[j] = rim.f(j * h);
    all_inside = all_inside && fs[j] < 1.0;
  }
  // g(t) = n_s . q'(t) = -D'(t): negative where the depth still rises.
  auto closest = [&](double t) { return closest_point_on_ellipsoid(rim.at(t), body); };
  auto g = [&](double t) { return closest(t).normal.dot(rim.tangent(t)); };
  auto finish = [&](double t) {
    RimMax r;
    r.q = rim.at(t);
    r.cp = closest(t);
    return r;
  };
  if (all_inside) {
    // The whole circle lies in the body: its deepest sample, refined.
    int best = 0;
    double dbest = -1e300;
    for (int j = 0; j < N; ++j) {
      const double d = -closest(j * h).signed_distance;
      if (d > dbest) dbest = d, best = j;
    }
    const double a = (best - 1) * h, b = (best + 1) * h;
    const double ga = g(a), gb = g(b);
    out[0] = finish(ga <= 0.0 && gb >= 0.0 ? illinois(g, a, b, ga, gb) : best * h);
    return out[0].depth() > 0.0 ? 1 : 0;
  }
  int n = 0;
  double arc_start[2];  // left ends of the arcs found (one arc can hold two sampled minima)
  for (int j = 0; j < N && n < 2; ++j) {
    const int jl = (j + N - 1) % N, jr = (j + 1) % N;
    if (!(fs[j] <= fs[jl] && fs[j] < fs[jr])) continue;
    // The minimum of F near sample j (safeguarded Newton on F').
    double lo = (j - 1) * h, hi = (j + 1) * h, t = j * h;
    for (int it = 0; it < 50; ++it) {
      const double d1 = rim.df(t), d2 = rim.d2f(t);
      if (d1 < 0.0) lo = t; else hi = t;
      double tn = d2 > 0.0 ? t - d1 / d2 : 0.5 * (lo + hi);
      if (!(tn > lo && tn < hi)) tn = 0.5 * (lo + hi);
      if (std::abs(tn - t) < 1e-15 * (1.0 + std::abs(t))) { t = tn; break; }
      t = tn;
    }
    if (rim.f(t) >= 1.0) continue;
    // The arc where F < 1 around t: walk out to a sample with F >= 1, bisect.
    auto end = [&](int dir) {
      int k = j + dir;
      while (fs[((k % N) + N) % N] < 1.0) k += dir;
      double in = (k - dir) * h, outp = k * h;
      if (k - dir == j) in = t;
      for (int it = 0; it < 64; ++it) {
        const double mid = 0.5 * (in + outp);
        if (rim.f(mid) < 1.0) in = mid; else outp = mid;
      }
      return in;
    };
    const double a = end(-1), b = end(+1);
    bool seen = false;
    for (int m = 0; m < n; ++m)
      seen = seen || std::abs(std::remainder(arc_start[m] - a, 2.0 * std::numbers::pi)) < 1e-9;
    if (seen) continue;
    arc_start[n] = a;
    const double ga = g(a), gb = g(b);
    const double root = ga <= 0.0 && gb >= 0.0 ? illinois(g, a, b, ga, gb) : t;
    out[n] = finish(root);
    if (out[n].depth() > 0.0) ++n;
  }
  return n;
}

ContactGeometry rim_contact(const SymMat3& q, const RimMax& r) {
  ContactGeometry g;
  g.normal = -r.cp.normal;
  g.overlap = r.depth();
  g.point = r.q;
  Vector3d t1, t2;
  tangent_basis(r.cp.normal, t1, t2);
  g.radius = hertz_radius(curvature_tensor(q, r.cp.normal, t1, t2));
  return g;
}

}  // namespace

AnnulusContacts ellipsoid_annulus_contacts(const Ellipsoid& body, const Annulus& wall) {
  AnnulusContacts out;
  const Vector3d& n = wall.normal;
  const Vector3d rel = body.centre - wall.centre;
  const double hn = n.dot(rel);
  const Vector3d m = hn >= 0.0 ? Vector3d(n) : Vector3d(-n);
  bool reaches = false;
  const ContactGeometry face = ellipsoid_plane_contact(body, Plane{wall.centre, m}, &reaches);
  if (!reaches) return out;  // the body does not reach the plane of the sheet
  // Foot on the plane of the deepest point.
  const Vector3d q0 = face.point + 0.5 * face.overlap * m;
  const double rho0 = (q0 - wall.centre).norm();
  const bool on_face = rho0 >= wall.r_in && rho0 <= wall.r_out;

  struct Candidate {
    ContactGeometry g;
    bool face;
  };
  Candidate cand[5];
  int nc = 0;
  if (on_face) cand[nc++] = {face, true};

  // Quadratic form, rotation and the rim's frame in body axes: set up only
  // when a rim passes the quick reject (most bodies on a face are far from it).
  const double bound = body.semi_axes.maxCoeff();
  const double rho_x = (rel - hn * n).norm();
  bool ready = false;
  SymMat3 q{};
  Mat3 rot = Mat3::Identity();
  Vector3d e1, e2;
  tangent_basis(n, e1, e2);
  double wdd = 0, wd1 = 0, wd2 = 0, w11 = 0, w12 = 0, w22 = 0;  // (Q^-1-weighted dots of d, e1, e2)
  for (const double rho : {wall.r_in, wall.r_out}) {
    if (!(rho > 0.0) || !std::isfinite(rho)) continue;
    // Off the faces, only the rim on q0's side: the body's section reaches
    // the other one across a face, which that rim's contact already holds.
    if (!on_face && (rho0 < wall.r_in) != (rho == wall.r_in)) continue;
    // Quick reject: the circle stays farther from the centre than the body reaches.
    if (hn * hn + (rho_x - rho) * (rho_x - rho) >= bound * bound) continue;
    if (!ready) {
      ready = true;
      q = body.form();
      rot = body.orientation.toRotationMatrix();
      const Vector3d w = body.semi_axes.cwiseProduct(body.semi_axes).cwiseInverse();
      const Vector3d db = rot.transpose() * (wall.centre - body.centre);
      const Vector3d e1b = rot.transpose() * e1, e2b = rot.transpose() * e2;
      wdd = db.cwiseProduct(w).dot(db);
      wd1 = db.cwiseProduct(w).dot(e1b);
      wd2 = db.cwiseProduct(w).dot(e2b);
      w11 = e1b.cwiseProduct(w).dot(e1b);
      w12 = e1b.cwiseProduct(w).dot(e2b);
      w22 = e2b.cwiseProduct(w).dot(e2b);
    }
    RimCircle rim;
    rim.c = wall.centre;
    rim.e1 = e1;
    rim.e2 = e2;
    rim.rho = rho;
    rim.k[0] = wdd;
    rim.k[1] = 2.0 * rho * wd1;
    rim.k[2] = 2.0 * rho * wd2;
    rim.k[3] = rho * rho * w11;
    rim.k[4] = 2.0 * rho * rho * w12;
    rim.k[5] = rho * rho * w22;
    RimMax maxima[2];
    const int nm = rim_maxima(body, rim, maxima);
    for (int k = 0; k < nm; ++k) {
      if (on_face) {
        // Counted only if the part of the section it holds is cut off from
        // q0 by the hole: the segment q0 -> q passes through the open hole.
        const Vector3d a = q0 - wall.centre, b = maxima[k].q - wall.centre;
        const Vector3d ab = b - a;
        const double len2 = ab.squaredNorm();
        const double s = len2 > 0.0 ? std::clamp(-a.dot(ab) / len2, 0.0, 1.0) : 0.0;
        const double dmin = (a + s * ab).norm();
        if (!(dmin < wall.r_in * (1.0 - 1e-9))) continue;
      }
      cand[nc++] = {rim_contact(q, maxima[k]), false};
    }
  }
  // The deepest face contact first, then the deepest rims; at most two.
  auto before = [](const Candidate& a, const Candidate& b) {
    return a.face != b.face ? a.face : a.g.overlap > b.g.overlap;
  };
  for (int k = 1; k < nc; ++k)  // insertion sort of at most five
    for (int j = k; j > 0 && before(cand[j], cand[j - 1]); --j) std::swap(cand[j], cand[j - 1]);
  out.count = std::min(nc, 2);
  for (int k = 0; k < out.count; ++k) {
    out.g[k] = cand[k].g;
    out.face[k] = cand[k].face;
  }
  if (out.count > 0 && !out.face[0]) {  // rims only (then `rot` is set)
    int longest = 0;
    body.semi_axes.maxCoeff(&longest);
    out.slot[0] = (out.g[0].point - body.centre).dot(rot.col(longest)) >= 0.0 ? 0 : 1;
    out.slot[1] = 1 - out.slot[0];
  }
  return out;
}

}  // namespace grains::contact
