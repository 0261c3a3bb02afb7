#!/usr/bin/env python3
"""Settled beds of any size for bench/scale, from one periodic seed bed.

  tile.py SEED.vtu KX KY STEPS OUTDIR [--vtk 0|1] [--liggghts-max N]
          [--seed-case CASE.yaml]

Repeats the seed's grains (the last frame of bench/scale/seed.yaml: a bed at
rest in a box periodic in x and y) KX times along x and KY times along y. The
seed being periodic, the copies join without seams: every bed has the same
local structure, and only its size differs. Writes into OUTDIR:

  positions.txt   'x y z r' per grain (grains, placement {type: file})
  case.yaml       the grains case: the tiled box, periodic in x and y, on the
                  seed's floor, with the seed's physics, for STEPS steps
  atoms.data      the same grains for LIGGGHTS (read_data, atom_style granular;
                  not written for beds of more than --liggghts-max grains)
  bed.env         shell assignments: N L_X L_Y Z_TOP STEPS DT

The grains start at rest where the seed left them; the first steps let the
copies settle into each other's weight (nothing moves more than a small part
of a diameter: the beds are alike at every size).

--seed-case names the case that made the seed (default: seed.yaml here; the
polydisperse seeds are in poly/): its box, physics and neighbour settings go
into case.yaml. Polydisperse seeds keep each grain's radius (positions.txt
carries it).
"""
import os
import re
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def read_seed(path):
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    if g.GetNumberOfPoints() == 0:
        sys.exit("tile.py: no grains in %s" % path)
    x = vtk_to_numpy(g.GetPoints().GetData()).astype(np.float64)
    rad = vtk_to_numpy(g.GetPointData().GetArray("radius")).astype(np.float64)
    return x, rad


def seed_params(case_path):
    t = open(case_path).read()

    def num(key):
        m = re.search(r"^\s*(?:-\s*)?%s:\s*([-+0-9.eE]+)" % key, t, re.M)
        if not m:
            sys.exit("tile.py: key '%s' not found in %s" % (key, case_path))
        return float(m.group(1))

    dmin = [float(v) for v in re.search(r"min:\s*\[([^\]]*)\]", t).group(1).split(",")]
    dmax = [float(v) for v in re.search(r"max:\s*\[([^\]]*)\]", t).group(1).split(",")]
    return {"lo": dmin, "hi": dmax, "density": num("density"), "E": num("youngs_modulus"),
            "nu": num("poisson_ratio"), "e": num("restitution"), "mu": num("friction"),
            "dt": num("dt"), "skin": num("skin"),
            "skin_per_grain": re.search(r"^\s*skin_per_grain:\s*true", t, re.M) is not None}


CASE = """# A settled bed of {n} spheres for bench/scale (written by bench/scale/tile.py):
# {kx} x {ky} copies of the seed bed of bench/scale/{seed_name}, periodic in x and y.
title: scale_{n}
domain:
  min: [0.0, 0.0, {zlo!r}]
  max: [{lx!r}, {ly!r}, {zhi!r}]
  periodic: [true, true, false]
gravity: [0, 0, -9.81]
materials:
  - name: grain
    density: {density!r}
    youngs_modulus: {E!r}
    poisson_ratio: {nu!r}
    restitution: {e!r}
    friction: {mu!r}
    rolling_friction: 0.0
particles:
  - name: spheres
    material: grain
    radius: {r!r}
    placement: {{type: file, path: positions.txt}}
walls:
  - {{type: plane, name: floor, point: [0, 0, 0], normal: [0, 0, 1], material: grain}}
time:
  dt: {dt!r}
  end: {end!r}
neighbor:
  skin: {skin!r}
  skin_per_grain: {skin_per_grain}
  overlap_tolerance: {tolerance}  # {tolerance_why}
output:
  every_steps: {steps}
  vtk: {vtk}
  progress_interval: 30
"""


def write_liggghts_data(path, x, r, density, kx, ky, box):
    n = len(x)
    with open(path, "w") as f:
        f.write("bench/scale: %d spheres, %d x %d copies of the seed bed\n\n" % (n, kx, ky))
        f.write("%d atoms\n1 atom types\n\n" % n)
        f.write("0 %r xlo xhi\n0 %r ylo yhi\n%r %r zlo zhi\n\nAtoms\n\n" % box)
        ids = np.arange(1, n + 1)
        np.savetxt(f, np.column_stack([ids, np.ones(n), 2 * r, np.full(n, density), x]),
                   fmt=["%d", "%d", "%.17g", "%.17g", "%.17g", "%.17g", "%.17g"])


def main():
    args = sys.argv[1:]
    vtk_out = "true"
    if "--vtk" in args:
        i = args.index("--vtk")
        vtk_out = "true" if args[i + 1] == "1" else "false"
        del args[i:i + 2]
    seed_case = None
    if "--seed-case" in args:
        i = args.index("--seed-case")
        seed_case = args[i + 1]
        del args[i:i + 2]
    liggghts_max = None
    if "--liggghts-max" in args:
        i = args.index("--liggghts-max")
        liggghts_max = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 5:
        sys.exit(__doc__)
    seed_vtu, kx, ky, steps, out = args[0], int(args[1]), int(args[2]), int(args[3]), args[4]
    here = os.path.dirname(os.path.abspath(__file__))
    seed_case = seed_case or os.path.join(here, "seed.yaml")
    p = seed_params(seed_case)
    x, rad = read_seed(seed_vtu)
    lx0, ly0 = p["hi"][0] - p["lo"][0], p["hi"][1] - p["lo"][1]
    if p["lo"][0] != 0 or p["lo"][1] != 0:
        sys.exit("tile.py: the seed's box should start at x = y = 0")
    x[:, 0] %= lx0  # the frame may hold grains just across a periodic face
    x[:, 1] %= ly0
    n0 = len(x)
    n = n0 * kx * ky
    os.makedirs(out, exist_ok=True)
    shift = np.array([[i * lx0, j * ly0, 0.0] for j in range(ky) for i in range(kx)])
    big = (x[None, :, :] + shift[:, None, :]).reshape(-1, 3)
    rr = np.tile(rad, kx * ky)
    z_top = float(x[:, 2].max() + rad.max())
    zhi = max(p["hi"][2], z_top + 10 * 2 * rad.max())
    with open(os.path.join(out, "positions.txt"), "w") as f:
        f.write("# %d spheres: %d x %d copies of %s (bench/scale/tile.py)\n" % (n, kx, ky, seed_vtu))
        np.savetxt(f, np.column_stack([big, rr]), fmt="%.17g")
    radius = float(rad.max())  # the file's radii replace it
    with open(os.path.join(out, "case.yaml"), "w") as f:
        f.write(CASE.format(n=n, kx=kx, ky=ky, zlo=p["lo"][2], lx=kx * lx0, ly=ky * ly0, zhi=zhi,
                            density=p["density"], E=p["E"], nu=p["nu"], e=p["e"], mu=p["mu"], r=radius,
                            dt=p["dt"], end=steps * p["dt"], skin=p["skin"], steps=steps, vtk=vtk_out,
                            skin_per_grain="true" if p["skin_per_grain"] else "false",
                            tolerance=0.05 if rad.max() == rad.min() else 0.2,
                            tolerance_why="a bed at rest carries its weight on overlaps of about 1 % of a radius"
                            if rad.max() == rad.min() else
                            "a small grain under a large one carries it on overlaps of 5-10 % of its radius",
                            seed_name=os.path.relpath(os.path.abspath(seed_case), here)))
    if liggghts_max is None or n <= liggghts_max:
        write_liggghts_data(os.path.join(out, "atoms.data"), big, rr, p["density"], kx, ky,
                            (kx * lx0, ky * ly0, p["lo"][2], zhi))
    with open(os.path.join(out, "bed.env"), "w") as f:
        f.write("N=%d\nL_X=%r\nL_Y=%r\nZ_TOP=%r\nZ_HI=%r\nSTEPS=%d\nDT=%r\nSKIN=%r\nRADIUS=%r\n" %
                (n, kx * lx0, ky * ly0, z_top, zhi, steps, p["dt"], p["skin"] * 2 * radius, radius))
        f.write("E=%r\nNU=%r\nREST=%r\nMU=%r\nZ_LO=%r\n" % (p["E"], p["nu"], p["e"], p["mu"], p["lo"][2]))
        f.write("RMIN=%r\n" % float(rad.min()))
    print("tile.py: %d grains (%d x %d copies) in %s" % (n, kx, ky, out))


if __name__ == "__main__":
    main()
