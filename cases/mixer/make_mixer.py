#!/usr/bin/env python3
"""Writes the meshes of cases/mixer (ASCII STL, metres):
  vessel.stl  an open-topped cylindrical vessel about the z axis (radius R,
              height H; its side and its flat bottom), faces towards the inside;
  blade.stl   a two-bladed paddle: two flat rectangular blades on a shaft
              along z, each blade from the shaft (radius s) out to radius b,
              of height h, tilted by `pitch` degrees about its own radial line
              (a pitched-blade agitator), its lower edge at z0; the shaft ends
              just above the blades.

    python3 make_mixer.py [R H b h pitch]   (default 0.03 0.05 0.024 0.008 45)
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import stl  # noqa: E402  (cases/stl.py)

a = [float(x) for x in sys.argv[1:]]
R = a[0] if len(a) > 0 else 0.03
H = a[1] if len(a) > 1 else 0.05
b = a[2] if len(a) > 2 else 0.024
h = a[3] if len(a) > 3 else 0.008
pitch = math.radians(a[4] if len(a) > 4 else 45.0)
s, z0, N = 0.003, 0.003, 64

# The vessel: side in 4 rings, bottom as a fan about the axis.
ring = lambda r, z: [(r * math.cos(2 * math.pi * k / N), r * math.sin(2 * math.pi * k / N), z) for k in range(N)]
tris = []
zs = [0.0, H / 4, H / 2, 3 * H / 4, H]
for za, zb in zip(zs, zs[1:]):
    A, B = ring(R, za), ring(R, zb)
    for k in range(N):
        k2 = (k + 1) % N
        tris += [(A[k], B[k2], A[k2]), (A[k], B[k], B[k2])]
bottom = ring(R, 0.0)
for k in range(N):
    tris.append(((0.0, 0.0, 0.0), bottom[(k + 1) % N], bottom[k]))
stl.write_ascii("vessel.stl", tris, "vessel")

# The paddle: each blade a rectangle from radius s to b, pitched about its radial line.
tris = []
for side in (0.0, math.pi):
    e = (math.cos(side), math.sin(side), 0.0)          # radial direction
    t = (-math.sin(side), math.cos(side), 0.0)         # tangential direction
    d = (t[0] * math.sin(pitch), t[1] * math.sin(pitch), math.cos(pitch))  # the blade's height direction
    zc = z0
    corner = lambda r, q: (e[0] * r + d[0] * q, e[1] * r + d[1] * q, zc + d[2] * q)
    p00, p10, p11, p01 = corner(s, 0), corner(b, 0), corner(b, h), corner(s, h)
    tris += [(p00, p10, p11), (p00, p11, p01)]
# The shaft: a thin square prism from z0 to just above the blades (the grains are poured from above it).
q = s * 0.7
sq = [(q, q), (-q, q), (-q, -q), (q, -q)]
for k in range(4):
    (x0, y0), (x1, y1) = sq[k], sq[(k + 1) % 4]
    top = z0 + h * math.cos(pitch) + 0.0018
    tris += [((x0, y0, z0), (x1, y1, z0), (x1, y1, top)), ((x0, y0, z0), (x1, y1, top), (x0, y0, top))]
stl.write_ascii("blade.stl", tris, "blade")
print("vessel.stl and blade.stl written")
