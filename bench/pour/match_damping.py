#!/usr/bin/env python3
"""The LIGGGHTS coefficientRestitution that reproduces grains's normal and
tangential damping coefficients exactly (bench/pour).

Both codes damp Hertz contacts with the same functional form,
    eta_n = a sqrt(m* K) d^(1/4),  K = 4/3 E* sqrt(R*),
    eta_t = a sqrt(2/3) sqrt(m* k_t),
and differ only in the dimensionless a:
  * grains calibrates a so that the *clamped* law (no attraction) achieves the
    requested restitution e: it solves u'' = -max(0, u^(3/2) + a u^(1/4) u'),
    u(0) = 0, u'(0) = 1 and inverts e(a) = -u'(exit);
  * LIGGGHTS uses a = -sqrt(5) beta, beta = ln e / sqrt(ln^2 e + pi^2).
Given grains's e, this prints a and the e_L with -sqrt(5) beta(e_L) = a, so
LIGGGHTS (limitForce on) runs the same force law. Independent of the grains
sources (own RK4 integration).

Usage: match_damping.py [e]     (default 0.5); prints 'a e_L'
"""
import math
import sys


def accel(u, w, a):
    if u <= 0:
        return 0.0
    s = math.sqrt(u)
    f = u * s + a * math.sqrt(s) * w
    return -f if f > 0 else 0.0


def restitution(a, h=1e-4):
    u, w = 0.0, 1.0
    k = 0
    while True:
        k1u, k1w = w, accel(u, w, a)
        k2u, k2w = w + 0.5 * h * k1w, accel(u + 0.5 * h * k1u, w + 0.5 * h * k1w, a)
        k3u, k3w = w + 0.5 * h * k2w, accel(u + 0.5 * h * k2u, w + 0.5 * h * k2w, a)
        k4u, k4w = w + h * k3w, accel(u + h * k3u, w + h * k3w, a)
        un = u + h / 6 * (k1u + 2 * k2u + 2 * k3u + k4u)
        wn = w + h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w)
        k += 1
        if un <= 0 and k > 1:
            t = u / (u - un)
            return -(w + t * (wn - w))
        u, w = un, wn
        if w < 0 and accel(u, w, a) == 0.0:  # clamped: leaves with constant speed
            return -w


def damping_for(e):
    lo, hi = 0.0, 1.0
    while restitution(hi) > e:
        lo, hi = hi, 2 * hi
    while hi - lo > 1e-7 * hi:
        mid = 0.5 * (lo + hi)
        if restitution(mid) > e:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main():
    e = float(sys.argv[1]) if len(sys.argv) > 1 else 0.5
    a = damping_for(e)
    beta = -a / math.sqrt(5.0)
    e_l = math.exp(beta * math.pi / math.sqrt(1.0 - beta * beta))
    print("%.10g %.10g" % (a, e_l))


if __name__ == "__main__":
    main()
