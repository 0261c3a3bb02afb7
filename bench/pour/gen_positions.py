#!/usr/bin/env python3
"""One set of initial positions for the serial pour benchmark (bench/pour).

Random sequential addition of N equal spheres in the fill region of
cases/pour_spheres (centres at least one radius inside the region, no two
spheres overlapping), with a fixed seed so the scene is reproducible. Writes
two files describing the same particles:

  positions.txt  'x y z' per line, for grains (placement: {type: file})
  atoms.data     LIGGGHTS read_data file (atom_style granular:
                 id type diameter density x y z)

Usage: gen_positions.py OUTDIR [N [seed [R RHO L H "DOMAIN(6 numbers)"]]]
"""
import math
import random
import sys

R = 0.0005                      # radius, m        (run.sh passes the case's values)
RHO = 2500.0                    # density, kg/m^3
REGION_LO = (0.0, 0.0, 0.0)     # fill region [0, L] x [0, L] x [0, H]
REGION_HI = (0.02, 0.02, 0.07)
BOX_LO = (-0.001, -0.001, -0.001)  # simulation domain
BOX_HI = (0.021, 0.021, 0.071)


def place(n, seed):
    rng = random.Random(seed)
    lo = [a + R for a in REGION_LO]
    hi = [b - R for b in REGION_HI]
    cell = 2 * R
    grid = {}
    pts = []
    min2 = (2 * R) ** 2
    attempts = 0
    while len(pts) < n:
        attempts += 1
        if attempts > 200 * n:
            sys.exit("gen_positions: could not place %d spheres" % n)
        x = tuple(lo[d] + rng.random() * (hi[d] - lo[d]) for d in range(3))
        c = tuple(int(math.floor(x[d] / cell)) for d in range(3))
        ok = True
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in grid.get((c[0] + dx, c[1] + dy, c[2] + dz), ()):
                        y = pts[j]
                        if (x[0] - y[0]) ** 2 + (x[1] - y[1]) ** 2 + (x[2] - y[2]) ** 2 < min2:
                            ok = False
                            break
                    if not ok:
                        break
                if not ok:
                    break
            if not ok:
                break
        if ok:
            grid.setdefault(c, []).append(len(pts))
            pts.append(x)
    return pts


def main():
    global R, RHO, REGION_HI, BOX_LO, BOX_HI
    out = sys.argv[1]
    if len(sys.argv) > 4:
        R, RHO, l, h = (float(v) for v in sys.argv[4:8])
        REGION_HI = (l, l, h)
        dom = [float(v) for v in sys.argv[8].split()]
        BOX_LO, BOX_HI = tuple(dom[:3]), tuple(dom[3:])
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 10000
    seed = int(sys.argv[3]) if len(sys.argv) > 3 else 2026
    pts = place(n, seed)
    with open(out + "/positions.txt", "w") as f:
        f.write("# %d spheres, r = %g m, seed %d (bench/pour/gen_positions.py)\n" % (n, R, seed))
        for p in pts:
            f.write("%.17g %.17g %.17g\n" % p)
    with open(out + "/atoms.data", "w") as f:
        f.write("bench/pour: %d spheres, d = %g m, rho = %g kg/m^3, seed %d\n\n" % (n, 2 * R, RHO, seed))
        f.write("%d atoms\n1 atom types\n\n" % n)
        for d, name in enumerate("xyz"):
            f.write("%.17g %.17g %slo %shi\n" % (BOX_LO[d], BOX_HI[d], name, name))
        f.write("\nAtoms\n\n")
        for i, p in enumerate(pts):
            f.write("%d 1 %.17g %.17g %.17g %.17g %.17g\n" % (i + 1, 2 * R, RHO, p[0], p[1], p[2]))
    print("gen_positions: %d spheres written to %s/{positions.txt,atoms.data}" % (n, out))


if __name__ == "__main__":
    main()
