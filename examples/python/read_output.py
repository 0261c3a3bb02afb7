"""Reading a finished run's output into numpy: frames (VTK), summary.json.

    PYTHONPATH=build/python python3 examples/python/read_output.py [--out DIR]

Runs a short pour from Python, then reads its frames back and compares the
last one with the simulation's own arrays at the end.
"""
import argparse

import numpy as np

import grains

CASE = {
    "title": "read_output",
    "domain": {"min": [-0.001, -0.001, -0.001], "max": [0.011, 0.011, 0.031]},
    "gravity": [0, 0, -9.81],
    "materials": [{"name": "grain", "density": 2500, "youngs_modulus": 1.0e7, "poisson_ratio": 0.3,
                   "restitution": 0.5, "friction": 0.5}],
    "particles": [{"name": "grains", "material": "grain", "radius": 0.0005, "count": 200,
                   "placement": {"type": "random_fill", "seed": 2,
                                 "region": {"min": [0, 0, 0], "max": [0.01, 0.01, 0.03]}}}],
    "walls": [{"type": "plane", "name": "floor", "point": [0, 0, 0], "normal": [0, 0, 1], "material": "grain"},
              {"type": "plane", "name": "x0", "point": [0, 0, 0], "normal": [1, 0, 0], "material": "grain"},
              {"type": "plane", "name": "x1", "point": [0.01, 0, 0], "normal": [-1, 0, 0], "material": "grain"},
              {"type": "plane", "name": "y0", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "grain"},
              {"type": "plane", "name": "y1", "point": [0, 0.01, 0], "normal": [0, -1, 0], "material": "grain"}],
    "time": {"dt": 8.0e-6, "end": 0.02},
    "output": {"every": 0.005, "progress": False},
}


def main(out):
    with grains.Simulation(CASE, out=out) as sim:
        sim.run()
        final = {"ids": sim.ids.copy(), "positions": sim.positions.copy()}
    frames = grains.output.read_frames(out)
    for f in frames:
        print("t = %.4f s: %d grains, mean height %.3f mm, mean speed %.4f m/s"
              % (f.time, len(f.points), 1e3 * f.points[:, 2].mean(), np.linalg.norm(f["velocity"], axis=1).mean()))
    last = frames[-1]
    a = np.argsort(last["id"])
    b = np.argsort(final["ids"])
    gap = np.abs(last.points[a] - final["positions"][b]).max()
    print("last frame against the simulation's arrays: largest difference %.3g m" % gap)
    s = grains.output.read_summary(out)
    print("summary: %d steps, %.3g particle-steps/s" % (s["steps"], s["particle_steps_per_second"]))
    return frames, final, gap


if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default="out/read_output")
    main(p.parse_args().out)
