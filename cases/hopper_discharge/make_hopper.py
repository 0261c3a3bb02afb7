#!/usr/bin/env python3
"""Writes hopper.stl (ASCII STL, metres): an open conical hopper with a
circular orifice at the bottom and a cylindrical bin above it, about the z
axis: the cone from the orifice (radius r0 at z = 0) up to the bin's radius
R, its half-angle theta from the vertical, then the bin up to height H above
the cone. Open at the top and at the orifice (a mesh wall needs no closed
surface). Also writes gate.obj: a square plate just below the orifice that
closes it while the hopper fills (case.yaml slides it away).

    python3 make_hopper.py [theta_deg] [r0] [R] [H] [segments]   (default 30 0.003 0.01 0.03 64)
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import stl  # noqa: E402  (cases/stl.py)

args = [float(a) for a in sys.argv[1:]]
theta = math.radians(args[0] if len(args) > 0 else 30.0)
r0 = args[1] if len(args) > 1 else 0.003
R = args[2] if len(args) > 2 else 0.010
H = args[3] if len(args) > 3 else 0.030
N = int(args[4]) if len(args) > 4 else 64

hc = (R - r0) / math.tan(theta)  # height of the cone
rings = [(r0, 0.0), (R, hc), (R, hc + H / 2), (R, hc + H)]

def point(r, z, k):
    t = 2 * math.pi * k / N
    return (r * math.cos(t), r * math.sin(t), z)

tris = []
for (ra, za), (rb, zb) in zip(rings, rings[1:]):
    for k in range(N):
        a, b = point(ra, za, k), point(ra, za, k + 1)
        c, d = point(rb, zb, k + 1), point(rb, zb, k)
        tris += [(a, c, b), (a, d, c)]  # wound with the normal towards the axis

stl.write_ascii("hopper.stl", tris, "hopper")

g = 1.5 * r0 + 0.001  # half-width of the gate
z = -0.0001
with open("gate.obj", "w") as f:
    f.write("# the gate under the orifice\n")
    for x, y in [(-g, -g), (g, -g), (g, g), (-g, g)]:
        f.write("v %.12g %.12g %.12g\n" % (x, y, z))
    f.write("f 1 2 3 4\n")
print("hopper.stl: %d triangles, cone height %.4g m, top at %.4g m; gate.obj" % (len(tris), hc, hc + H))
