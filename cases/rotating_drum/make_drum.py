#!/usr/bin/env python3
"""Writes drum.stl: a closed drum (a cylinder about the y axis with both end
caps), the rotating drum of cases/rotating_drum. Binary STL, metres, its
centre at the origin, faces wound counter-clockwise seen from outside.

    python3 make_drum.py [radius] [length] [segments]   (default 0.05 0.024 96)
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import stl  # noqa: E402  (cases/stl.py)

R = float(sys.argv[1]) if len(sys.argv) > 1 else 0.05
L = float(sys.argv[2]) if len(sys.argv) > 2 else 0.024
N = int(sys.argv[3]) if len(sys.argv) > 3 else 96

def ring(y):
    return [(R * math.cos(2 * math.pi * k / N), y, R * math.sin(2 * math.pi * k / N)) for k in range(N)]

a, b = ring(-L / 2), ring(L / 2)
c0, c1 = (0.0, -L / 2, 0.0), (0.0, L / 2, 0.0)
tris = []
for k in range(N):
    k2 = (k + 1) % N
    # side (outward normal radial), then the end caps (normals -y and +y)
    tris += [(a[k], b[k2], a[k2]), (a[k], b[k], b[k2])]
    tris += [(c0, a[k], a[k2]), (c1, b[k2], b[k])]

stl.write_binary("drum.stl", tris, b"grains rotating drum R=%g L=%g N=%d" % (R, L, N))
print("drum.stl:", len(tris), "triangles")
