#!/usr/bin/env python3
"""Reads the scene of cases/rotating_drum/case.yaml for bench/drum, so that the
benchmark follows the case file (one source of truth), and prepares and checks
the inputs of both codes.

  scene.py params CASE.yaml           shell assignments: N R RHO E NU REST MU G_X G_Y G_Z
                                      DT_RAYLEIGH SKIN SEED REGION DOMAIN MESH AXIS AXIS_POINT RPM
                                      DRUM_R DRUM_Y0 DRUM_Y1 (the last three from the STL's vertices)
  scene.py positions CASE.yaml OUT    one set of initial positions for both codes:
                                      OUT/positions.txt (grains placement {type: file}) and
                                      OUT/atoms.data (LIGGGHTS read_data), random sequential
                                      addition in the case's fill region with its seed
                                      (bench/pour/gen_positions.py's place(), imported)
  scene.py stl IN.stl OUT.stl         the mesh as ASCII STL (LIGGGHTS reads ASCII STL only)
  scene.py bed grains|liggghts FILE CASE.yaml
                                      final bed: particles, those inside the drum (centre within
                                      radius - r/2 of the axis and between the end caps),
                                      mean x and z of the centres (prints 'n inside xbar zbar')

Plain text handling (no YAML module on the target machine); it expects the
layout of the shipped case (one material, one particle set, one mesh wall).
"""
import math
import os
import re
import struct
import sys

sys.dont_write_bytecode = True  # no __pycache__ in bench/pour
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "pour"))


def num(text, key, default=None):
    m = re.search(r"^\s*(?:-\s*)?%s:\s*([-+0-9.eE]+)" % key, text, re.M)
    if not m:
        if default is not None:
            return default
        sys.exit("scene.py: key '%s' not found" % key)
    return float(m.group(1))


def vec(text, key, default=None):
    m = re.search(r"^\s*(?:-\s*)?%s:\s*\[([^\]]*)\]" % key, text, re.M)
    if not m:
        if default is not None:
            return default
        sys.exit("scene.py: key '%s' not found" % key)
    return [float(v) for v in m.group(1).split(",")]


def read_stl(path):
    """Triangles [(n, a, b, c)] of an ASCII or binary STL."""
    raw = open(path, "rb").read()
    tris = []
    if len(raw) >= 84:
        n = struct.unpack_from("<I", raw, 80)[0]
        if len(raw) == 84 + 50 * n:
            for k in range(n):
                v = struct.unpack_from("<12f", raw, 84 + 50 * k)
                tris.append((v[0:3], v[3:6], v[6:9], v[9:12]))
            return tris
    t = raw.decode(errors="replace")
    for m in re.finditer(r"facet\s+normal\s+(\S+)\s+(\S+)\s+(\S+)\s+outer\s+loop\s+"
                         r"vertex\s+(\S+)\s+(\S+)\s+(\S+)\s+vertex\s+(\S+)\s+(\S+)\s+(\S+)\s+"
                         r"vertex\s+(\S+)\s+(\S+)\s+(\S+)", t):
        v = [float(x) for x in m.groups()]
        tris.append((v[0:3], v[3:6], v[6:9], v[9:12]))
    if not tris:
        sys.exit("scene.py: no triangles in %s" % path)
    return tris


def case_mesh(path, text):
    m = re.search(r"^\s*file:\s*(\S+)", text, re.M)
    if not m:
        sys.exit("scene.py: no mesh file in %s" % path)
    return os.path.join(os.path.dirname(os.path.abspath(path)), m.group(1))


def params(path):
    t = open(path).read()
    if len(re.findall(r"^\s*-?\s*type:\s*mesh", t, re.M)) != 1 or re.search(r"type:\s*(plane|cylinder)", t):
        sys.exit("scene.py: expected exactly one wall, a mesh")
    for key in ("scale", "rotate_angle", "translate", "vibration_amplitude", "velocity", "angular_velocity"):
        if re.search(r"^\s*%s:" % key, t, re.M):
            sys.exit("scene.py: the benchmark does not handle '%s'" % key)
    r = num(t, "radius")
    region = re.search(r"region:\s*\{min:\s*\[([^\]]*)\],\s*max:\s*\[([^\]]*)\]", t)
    mesh = case_mesh(path, t)
    pts = [p for tri in read_stl(mesh) for p in tri[1:]]
    lo = [min(p[d] for p in pts) for d in range(3)]
    hi = [max(p[d] for p in pts) for d in range(3)]
    centre = [0.5 * (lo[d] + hi[d]) for d in range(3)]
    axis = vec(t, "axis", [0.0, 0.0, 1.0])
    axis_point = vec(t, "axis_point", centre)
    if [abs(a) for a in axis] != [0.0, 1.0, 0.0] or abs(axis_point[0]) > 1e-12 or abs(axis_point[2]) > 1e-12:
        sys.exit("scene.py: expected a drum about the y axis through x = z = 0")
    g = vec(t, "gravity")
    p = {
        "N": int(num(t, "count")), "R": r, "RHO": num(t, "density"), "E": num(t, "youngs_modulus"),
        "NU": num(t, "poisson_ratio"), "REST": num(t, "restitution"), "MU": num(t, "friction"),
        "MUR": num(t, "rolling_friction", 0.0), "G_X": g[0], "G_Y": g[1], "G_Z": g[2],
        "DT_RAYLEIGH": num(t, "dt_rayleigh"), "SKIN": num(t, "skin", 0.1) * 2 * r,
        "SEED": int(num(t, "seed", 1)),
        "REGION": " ".join("%r" % float(v) for v in region.group(1).split(",") + region.group(2).split(",")),
        "DOMAIN": " ".join("%r" % v for v in vec(t, "min") + vec(t, "max")),
        "MESH": mesh, "AXIS": " ".join("%r" % v for v in axis),
        "AXIS_POINT": " ".join("%r" % v for v in axis_point), "RPM": num(t, "rpm"),
        "DRUM_R": max(math.hypot(q[0] - axis_point[0], q[2] - axis_point[2]) for q in pts),
        "DRUM_Y0": lo[1], "DRUM_Y1": hi[1],
    }
    if p["MUR"] != 0:
        sys.exit("scene.py: the benchmark expects rolling_friction 0")
    if len(re.findall(r"^\s*-\s*name:", t, re.M)) != 2:  # one material, one particle set
        sys.exit("scene.py: expected one material and one particle set")
    for k, v in p.items():
        print("%s='%s'" % (k, v))


def positions(path, out):
    import gen_positions as gp  # bench/pour: random sequential addition, fixed seed
    t = open(path).read()
    region = re.search(r"region:\s*\{min:\s*\[([^\]]*)\],\s*max:\s*\[([^\]]*)\]", t)
    gp.R = num(t, "radius")
    gp.REGION_LO = tuple(float(v) for v in region.group(1).split(","))
    gp.REGION_HI = tuple(float(v) for v in region.group(2).split(","))
    dom = vec(t, "min") + vec(t, "max")
    rho, n, seed = num(t, "density"), int(num(t, "count")), int(num(t, "seed", 1))
    pts = gp.place(n, seed)
    with open(out + "/positions.txt", "w") as f:
        f.write("# %d spheres, r = %g m, seed %d (bench/drum/scene.py, gen_positions.place)\n" % (n, gp.R, seed))
        for q in pts:
            f.write("%.17g %.17g %.17g\n" % q)
    with open(out + "/atoms.data", "w") as f:
        f.write("bench/drum: %d spheres, d = %g m, rho = %g kg/m^3, seed %d\n\n" % (n, 2 * gp.R, rho, seed))
        f.write("%d atoms\n1 atom types\n\n" % n)
        for d, name in enumerate("xyz"):
            f.write("%.17g %.17g %slo %shi\n" % (dom[d], dom[3 + d], name, name))
        f.write("\nAtoms\n\n")
        for i, q in enumerate(pts):
            f.write("%d 1 %.17g %.17g %.17g %.17g %.17g\n" % (i + 1, 2 * gp.R, rho, q[0], q[1], q[2]))
    print("scene.py: %d spheres written to %s/{positions.txt,atoms.data}" % (n, out))


def stl(src, dst):
    tris = read_stl(src)
    with open(dst, "w") as f:
        f.write("solid drum\n")
        for n, a, b, c in tris:
            f.write("  facet normal %.9g %.9g %.9g\n    outer loop\n" % tuple(n))
            for v in (a, b, c):
                f.write("      vertex %.9g %.9g %.9g\n" % tuple(v))
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid drum\n")


def bed(kind, path, case_path):
    import packing  # bench/pour: readers of grains's VTU frames and LIGGGHTS dumps
    t = open(case_path).read()
    pts = [q for tri in read_stl(case_mesh(case_path, t)) for q in tri[1:]]
    rd = max(math.hypot(q[0], q[2]) for q in pts)
    y0, y1 = min(q[1] for q in pts), max(q[1] for q in pts)
    x, r = packing.read_vtu(path) if kind == "grains" else packing.read_dump(path)
    inside = sum(1 for q, s in zip(x, r)
                 if math.hypot(q[0], q[2]) < rd - 0.5 * s and y0 + 0.5 * s < q[1] < y1 - 0.5 * s)
    n = len(x)
    print("%d %d %.5f %.5f" % (n, inside, sum(q[0] for q in x) / max(n, 1), sum(q[2] for q in x) / max(n, 1)))


if __name__ == "__main__":
    cmd = sys.argv[1] if len(sys.argv) > 1 else ""
    if cmd == "params":
        params(sys.argv[2])
    elif cmd == "positions":
        positions(sys.argv[2], sys.argv[3])
    elif cmd == "stl":
        stl(sys.argv[2], sys.argv[3])
    elif cmd == "bed":
        bed(sys.argv[2], sys.argv[3], sys.argv[4])
    else:
        sys.exit(__doc__)
