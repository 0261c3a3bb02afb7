"""A calibration loop: bisection on the sliding friction coefficient until a
poured bed's bulk packing fraction hits a target.

    PYTHONPATH=build/python python3 examples/python/calibrate_friction.py [--target 0.60] [--grains N]

Each evaluation pours N spheres into a box, lets them settle, and measures
the solid fraction of the slab of the bed away from the floor and the free
surface (spheres cut exactly by the slab's planes; the box is periodic in x
and y, so there are no side walls and no cut is needed there). Friction lowers the packing
fraction (measured here: 0.624 at friction 0.05, 0.603 at 0.2, 0.588 at 0.4, 0.577 at 1), so a bisection on it
converges.
"""
import argparse
import math
import sys

import numpy as np

import grains

SIDE = 0.004


def pour_case(n, friction, seed=7):
    # Periodic in x and y: a bulk bed without side walls.
    return {
        "title": "calibration_pour",
        "domain": {"min": [0, 0, -0.001], "max": [SIDE, SIDE, 0.021], "periodic": [True, True, False]},
        "gravity": [0, 0, -9.81],
        "materials": [{"name": "grain", "density": 2500, "youngs_modulus": 1.0e7, "poisson_ratio": 0.3,
                       "restitution": 0.3, "friction": friction}],
        "particles": [{"name": "grains", "material": "grain",
                       "radius": {"distribution": "uniform", "min": 0.00025, "max": 0.0003},
                       "count": n,
                       "placement": {"type": "random_fill", "seed": seed,
                                     "region": {"min": [0, 0, 0], "max": [SIDE, SIDE, 0.02]}}}],
        "walls": [{"type": "plane", "name": "floor", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "grain"}],
        "time": {"dt": 5.0e-6, "end": 0.6},
        "output": {"vtk": False, "progress": False},
    }


def slab_fraction(z, r, lo, hi, area):
    """Solid fraction of the slab lo < z < hi: each sphere's volume inside it."""
    def below(h):  # volume of each sphere under the plane z = h
        t = np.clip(h - (z - r), 0.0, 2 * r)
        return math.pi * t * t * (3 * r - t) / 3.0
    return float((below(hi) - below(lo)).sum() / (area * (hi - lo)))


def packing_fraction(friction, n, out):
    with grains.Simulation(pour_case(n, friction), out=out) as sim:
        sim.run(until=lambda s: s.time > 0.05 and np.abs(s.velocities).max() < 0.005, every=500)
        z, r = sim.positions[:, 2], sim.radii
        top = np.sort(z + r)[-max(1, n // 20):].mean()  # the surface: mean top of the highest 5 %
        return slab_fraction(z, r, 4 * r.max(), top - 4 * r.max(), SIDE * SIDE)


def calibrate(target, n=1000, lo=0.05, hi=1.0, tol=0.004, iterations=6, out="out/calibration", log=print):
    phi_lo, phi_hi = packing_fraction(lo, n, out + "/lo"), packing_fraction(hi, n, out + "/hi")
    log("friction %.3f: phi %.4f" % (lo, phi_lo))
    log("friction %.3f: phi %.4f" % (hi, phi_hi))
    if not (phi_hi <= target <= phi_lo):
        raise ValueError("the target %.4f is outside [%.4f, %.4f], what friction %.2f..%.2f gives"
                         % (target, phi_hi, phi_lo, lo, hi))
    mid, phi = lo, phi_lo
    for k in range(iterations):
        mid = 0.5 * (lo + hi)
        phi = packing_fraction(mid, n, "%s/%d" % (out, k))
        log("friction %.3f: phi %.4f" % (mid, phi))
        if abs(phi - target) <= tol:
            break
        if phi > target:
            lo = mid
        else:
            hi = mid
    return mid, phi


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--target", type=float, default=0.595)
    p.add_argument("--grains", type=int, default=1000)
    p.add_argument("--out", default="out/calibration")
    a = p.parse_args()
    try:
        mu, phi = calibrate(a.target, a.grains, out=a.out)
    except ValueError as e:
        sys.exit(str(e))
    print("friction %.3f gives phi %.4f (target %.4f)" % (mu, phi, a.target))
