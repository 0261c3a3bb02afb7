"""STL writing for the mesh generators of cases/*/make_*.py (imported by
them from this folder): triangles are triples of (x, y, z) points, wound
counter-clockwise seen from the side their normal points to."""
import math
import struct


def normal(t):
    """Unit normal of triangle t by the right-hand rule."""
    u = [t[1][i] - t[0][i] for i in range(3)]
    v = [t[2][i] - t[0][i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    s = math.sqrt(sum(x * x for x in n))
    return tuple(x / s for x in n)


def write_ascii(path, tris, name):
    with open(path, "w") as f:
        f.write("solid %s\n" % name)
        for t in tris:
            f.write("  facet normal %.9g %.9g %.9g\n    outer loop\n" % normal(t))
            for p in t:
                f.write("      vertex %.12g %.12g %.12g\n" % p)
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid %s\n" % name)


def write_binary(path, tris, header):
    with open(path, "wb") as f:
        f.write(header.ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", *normal(t)))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")
