#include "sim/integrate/rigid_body.hpp"

#include <cmath>
#include <cstddef>

namespace grains::sim {

namespace {

// Rotation matrix of a unit quaternion (the same formula as Eigen's
// toRotationMatrix), row-major.
struct Rot {
  double m00, m01, m02, m10, m11, m12, m20, m21, m22;
};

inline Rot rot(double w, double x, double y, double z) {
  const double tx = 2.0 * x, ty = 2.0 * y, tz = 2.0 * z;
  const double twx = tx * w, twy = ty * w, twz = tz * w;
  const double txx = tx * x, txy = ty * x, txz = tz * x;
  const double tyy = ty * y, tyz = tz * y, tzz = tz * z;
  return {1.0 - (tyy + tzz), txy - twz, txz + twy, txy + twz, 1.0 - (txx + tzz),
          tyz - twx,         txz - twy, tyz + twx, 1.0 - (txx + tyy)};
}

// omega = R I^-1 R^T L.
inline void world_omega(const Rot& R, double L0, double L1, double L2, double j0, double j1, double j2,
                        double* om) {
  const double c0 = (R.m00 * L0 + R.m10 * L1 + R.m20 * L2) * j0;
  const double c1 = (R.m01 * L0 + R.m11 * L1 + R.m21 * L2) * j1;
  const double c2 = (R.m02 * L0 + R.m12 * L1 + R.m22 * L2) * j2;
  om[0] = R.m00 * c0 + R.m01 * c1 + R.m02 * c2;
  om[1] = R.m10 * c0 + R.m11 * c1 + R.m12 * c2;
  om[2] = R.m20 * c0 + R.m21 * c1 + R.m22 * c2;
}

// v += half_dt F/m and L += half_dt T for particle i.
inline void half_kick(ParticleStore& p, std::ptrdiff_t i, double half_dt) {
  const double hm = half_dt * p.inv_mass[i];
  double* v = p.v[i].data();
  const double* f = p.f[i].data();
  v[0] += hm * f[0];
  v[1] += hm * f[1];
  v[2] += hm * f[2];
  double* L = p.angular_momentum[i].data();
  const double* t = p.torque[i].data();
  L[0] += half_dt * t[0];
  L[1] += half_dt * t[1];
  L[2] += half_dt * t[2];
}

}  // namespace

void rigid_half_kick(ParticleStore& p, double half_dt) {
  const auto n = static_cast<std::ptrdiff_t>(p.n_owned());
  parallel_for(use_threads(n, 1024), n, [&](std::ptrdiff_t i) {
    half_kick(p, i, half_dt);
    const double* L = p.angular_momentum[i].data();
    const double* I = p.inertia[i].data();
    const Quat& q = p.orientation[i];
    world_omega(rot(q.w(), q.x(), q.y(), q.z()), L[0], L[1], L[2], 1.0 / I[0], 1.0 / I[1], 1.0 / I[2],
                p.omega[i].data());
  });
}

void rigid_kick_drift(ParticleStore& p, std::size_t n, double dt) {
  const double half_dt = 0.5 * dt;
  const auto count = static_cast<std::ptrdiff_t>(n);
  parallel_for(use_threads(count, 1024), count, [&](std::ptrdiff_t i) {
    half_kick(p, i, half_dt);
    const double* v = p.v[i].data();
    const double* Lp = p.angular_momentum[i].data();
    const double L0 = Lp[0], L1 = Lp[1], L2 = Lp[2];
    const double* I = p.inertia[i].data();
    const double j0 = 1.0 / I[0], j1 = 1.0 / I[1], j2 = 1.0 / I[2];
    // Drift of the position.
    double* x = p.x[i].data();
    x[0] += dt * v[0];
    x[1] += dt * v[1];
    x[2] += dt * v[2];
    // Angular velocity at the half step (half_step_angular_velocity).
    Quat& q = p.orientation[i];
    const double qw = q.w(), qx = q.x(), qy = q.y(), qz = q.z();
    const Rot R0 = rot(qw, qx, qy, qz);
    const double b0 = R0.m00 * L0 + R0.m10 * L1 + R0.m20 * L2;  // L_b = R0^T L
    const double b1 = R0.m01 * L0 + R0.m11 * L1 + R0.m21 * L2;
    const double b2 = R0.m02 * L0 + R0.m12 * L1 + R0.m22 * L2;
    const double w0 = b0 * j0, w1 = b1 * j1, w2 = b2 * j2;  // w_b = I^-1 L_b
    const double m0 = w0 + half_dt * ((b1 * w2 - b2 * w1) * j0);
    const double m1 = w1 + half_dt * ((b2 * w0 - b0 * w2) * j1);
    const double m2 = w2 + half_dt * ((b0 * w1 - b1 * w0) * j2);
    const double a0 = R0.m00 * m0 + R0.m01 * m1 + R0.m02 * m2;  // world frame
    const double a1 = R0.m10 * m0 + R0.m11 * m1 + R0.m12 * m2;
    const double a2 = R0.m20 * m0 + R0.m21 * m1 + R0.m22 * m2;
    // q <- exp(dt w_mid) q (rotate(), same series and fallback).
    const double s2 = (a0 * a0 + a1 * a1 + a2 * a2) * dt * dt;
    double nw = qw, nx = qx, ny = qy, nz = qz;
    if (s2 != 0.0) {
      double rw, rs;  // rotation quaternion (rw, rs * a)
      if (s2 < 1e-4) {
        const double h2 = 0.25 * s2;
        rw = 1.0 - h2 * (0.5 - h2 * (1.0 / 24.0 - h2 * (1.0 / 720.0)));
        rs = 0.5 * dt * (1.0 - h2 * (1.0 / 6.0 - h2 * (1.0 / 120.0 - h2 * (1.0 / 5040.0))));
      } else {
        const double angle = std::sqrt(s2);
        rw = std::cos(0.5 * angle);
        rs = std::sin(0.5 * angle) * dt / angle;
      }
      const double rx = rs * a0, ry = rs * a1, rz = rs * a2;
      // r * q
      nw = rw * qw - rx * qx - ry * qy - rz * qz;
      nx = rw * qx + rx * qw + ry * qz - rz * qy;
      ny = rw * qy + ry * qw + rz * qx - rx * qz;
      nz = rw * qz + rz * qw + rx * qy - ry * qx;
      const double inv = 1.0 / std::sqrt(nw * nw + nx * nx + ny * ny + nz * nz);
      nw *= inv;
      nx *= inv;
      ny *= inv;
      nz *= inv;
      q.w() = nw;
      q.x() = nx;
      q.y() = ny;
      q.z() = nz;
    }
    // New angular velocity w = R I^-1 R^T L, and the PW85 form R diag(a^2) R^T.
    const Rot R = rot(nw, nx, ny, nz);
    world_omega(R, L0, L1, L2, j0, j1, j2, p.omega[i].data());
    if (p.shape[i] == kEllipsoid) {
      const double* ax = p.semi_axes[i].data();
      const double e0 = ax[0] * ax[0], e1 = ax[1] * ax[1], e2 = ax[2] * ax[2];
      auto& Q = p.form[i];
      Q[0] = R.m00 * e0 * R.m00 + R.m01 * e1 * R.m01 + R.m02 * e2 * R.m02;
      Q[1] = R.m00 * e0 * R.m10 + R.m01 * e1 * R.m11 + R.m02 * e2 * R.m12;
      Q[2] = R.m00 * e0 * R.m20 + R.m01 * e1 * R.m21 + R.m02 * e2 * R.m22;
      Q[3] = R.m10 * e0 * R.m10 + R.m11 * e1 * R.m11 + R.m12 * e2 * R.m12;
      Q[4] = R.m10 * e0 * R.m20 + R.m11 * e1 * R.m21 + R.m12 * e2 * R.m22;
      Q[5] = R.m20 * e0 * R.m20 + R.m21 * e1 * R.m21 + R.m22 * e2 * R.m22;
    }
  });
}

}  // namespace grains::sim
