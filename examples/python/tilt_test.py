"""A multi-stage tilt test: fill a box, let the bed settle, then tilt gravity
one degree at a time until the bed avalanches; report the angle.

    PYTHONPATH=build/python python3 examples/python/tilt_test.py [--grains N] [--out DIR]

The bed's free surface starts level, so the tilt at which it avalanches is
its maximum angle of stability; in a box 11 grains wide the side walls hold
the bed, so it exceeds a free heap's angle of repose, the more so the
deeper the bed (measured: 35-36 degrees with 300-400 grains, 48 with 800). Stages: (1) pour and settle until the
fastest grain moves slower than 5 mm/s; (2) turn gravity about y by one
degree every 10 ms and watch the mean speed along the slope; the avalanche
is the first tilt at which the upper half of the bed moves down the slope
faster than 5 mm/s on average at the end of the 10 ms hold.
"""
import argparse
import math
import sys

import numpy as np

import grains


def box_case(n, seed=3, friction=0.5, rolling=0.05):
    side = 0.01
    return {
        "title": "tilt_test",
        "domain": {"min": [-0.001, -0.001, -0.001], "max": [side + 0.001, side + 0.001, 0.041]},
        "gravity": [0, 0, -9.81],
        "materials": [{"name": "grain", "density": 2500, "youngs_modulus": 1.0e7, "poisson_ratio": 0.3,
                       "restitution": 0.3, "friction": friction, "rolling_friction": rolling}],
        "particles": [{"name": "grains", "material": "grain",
                       "radius": {"distribution": "uniform", "min": 0.0004, "max": 0.0005},
                       "count": n,
                       "placement": {"type": "random_fill", "seed": seed,
                                     "region": {"min": [0, 0, 0], "max": [side, side, 0.04]}}}],
        "walls": [
            {"type": "plane", "name": "floor", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "grain"},
            {"type": "plane", "name": "x0", "point": [0, 0, 0], "normal": [1, 0, 0], "material": "grain"},
            {"type": "plane", "name": "x1", "point": [side, 0, 0], "normal": [-1, 0, 0], "material": "grain"},
            {"type": "plane", "name": "y0", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "grain"},
            {"type": "plane", "name": "y1", "point": [0, side, 0], "normal": [0, -1, 0], "material": "grain"},
        ],
        "time": {"dt": 8.0e-6, "end": 1.0},
        "output": {"every": 0.05, "progress": False},
    }


def tilt_test(n=400, out="out/tilt_test", max_tilt=60, threshold=0.005, log=print):
    g = 9.81
    with grains.Simulation(grains.Case(box_case(n)), out=out) as sim:
        # Stage 1: fill and settle.
        sim.run(until=lambda s: s.time > 0.05 and np.abs(s.velocities).max() < threshold, every=250, max_time=0.6)
        speed = np.abs(sim.velocities).max()
        if speed >= threshold:
            raise RuntimeError("the bed did not settle by t = %.2f s (fastest grain %.3g m/s)" % (sim.time, speed))
        log("settled at t = %.3f s: bed height %.2f mm" % (sim.time, 1e3 * sim.positions[:, 2].max()))
        # Stage 2: tilt gravity about y, one degree at a time.
        hold = 0.01
        for deg in range(1, max_tilt + 1):
            a = math.radians(deg)
            sim.gravity = (g * math.sin(a), 0.0, -g * math.cos(a))
            sim.run(until=sim.time + hold, every=250)
            # The surface layer (the upper half of the bed) moving down the slope (+x).
            top = sim.positions[:, 2] > np.median(sim.positions[:, 2])
            along = float(sim.velocities[top, 0].mean())
            if along > threshold:
                log("tilt %2d deg: upper half's mean speed down the slope %.4f m/s: avalanche" % (deg, along))
                return deg
            log("tilt %2d deg: upper half's mean speed down the slope %.4f m/s" % (deg, along))
    return None


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--grains", type=int, default=400)
    p.add_argument("--out", default="out/tilt_test")
    a = p.parse_args()
    angle = tilt_test(a.grains, a.out)
    if angle is None:
        sys.exit("no avalanche up to 60 degrees")
    print("avalanche angle: %d degrees" % angle)
