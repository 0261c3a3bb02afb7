#!/usr/bin/env python3
"""Final bulk packing fraction of a poured bed (bench/pour), for grains and
LIGGGHTS alike, from their own output files:

  packing.py grains  FRAME.vtu     (grains's last particles frame; VTK XML, appended raw or base64, zlib)
  packing.py liggghts FILE.dump    (LIGGGHTS 'dump custom ... id x y z radius')

Bulk region: 3 d away from the four side walls and the floor, and 3 d below
the free surface, taken as the mean height of the top 400 centres (about one
layer of a 20 d x 20 d bed). The fraction is estimated with 400,000
quasi-random points (the same fixed set for both codes, so the difference
between the two beds is measured with correlated sampling); the standard
error is printed (about 1e-3).
"""
import binascii
import math
import re
import struct
import sys
import zlib

D = 0.001
L = 0.02


def read_vtu(path):
    raw = open(path, "rb").read()
    head_end = raw.find(b"<AppendedData")
    head = raw[:head_end].decode()
    m = re.search(r'header_type="(\w+)"', head)
    htype = "<Q" if (m is None or m.group(1) == "UInt64") else "<I"
    hsize = struct.calcsize(htype)
    compressed = "compressor=" in head
    base64 = b'encoding="base64"' in raw[head_end:head_end + 64]
    start = raw.index(b"_", head_end) + 1

    def b64(pos, nbytes):  # nbytes decoded from the base64 chunk starting at pos
        return binascii.a2b_base64(raw[pos:pos + 4 * ((nbytes + 2) // 3)])[:nbytes]

    def array(tag_match):
        attrs = dict(re.findall(r'(\w+)="([^"]*)"', tag_match))
        off = start + int(attrs["offset"])
        if base64:
            if compressed:  # header and compressed blocks: two base64 chunks
                nb = struct.unpack(htype, b64(off, hsize))[0]
                hlen = hsize * (3 + nb)
                csz = struct.unpack("<" + htype[1] * (3 + nb), b64(off, hlen))[3:]
                blob = b64(off + 4 * ((hlen + 2) // 3), sum(csz))
                data, p = b"", 0
                for c in csz:
                    data += zlib.decompress(blob[p:p + c])
                    p += c
            else:
                n = struct.unpack(htype, b64(off, hsize))[0]
                data = b64(off, hsize + n)[hsize:]
        elif compressed:
            nb = struct.unpack_from(htype, raw, off)[0]
            csz = struct.unpack_from("<" + htype[1] * (3 + nb), raw, off)[3:]
            p = off + hsize * (3 + nb)
            data = b""
            for c in csz:
                data += zlib.decompress(raw[p:p + c])
                p += c
        else:
            n = struct.unpack_from(htype, raw, off)[0]
            data = raw[off + hsize: off + hsize + n]
        fmt = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i"}[attrs["type"]]
        return struct.unpack("<%d%s" % (len(data) // struct.calcsize(fmt), fmt), data)

    pts_tag = re.search(r"<Points>\s*(<DataArray[^>]*>)", head).group(1)
    xyz = array(pts_tag)
    rad_tag = re.search(r'(<DataArray[^>]*Name="radius"[^>]*>)', head).group(1)
    r = array(rad_tag)
    x = [(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]) for i in range(len(r))]
    return x, list(r)


def read_dump(path):
    lines = open(path).read().splitlines()
    k = max(i for i, s in enumerate(lines) if s.startswith("ITEM: ATOMS"))
    cols = lines[k].split()[2:]
    ix, iy, iz, ir = (cols.index(c) for c in ("x", "y", "z", "radius"))
    x, r = [], []
    for s in lines[k + 1:]:
        f = s.split()
        if len(f) < len(cols):
            continue
        x.append((float(f[ix]), float(f[iy]), float(f[iz])))
        r.append(float(f[ir]))
    return x, r


def bulk_fraction(x, r, npts=400000):
    top = sorted(p[2] for p in x)[-400:]
    surface = sum(top) / len(top)
    lo = (3 * D, 3 * D, 3 * D)
    hi = (L - 3 * D, L - 3 * D, surface - 3 * D)
    rmax = max(r)
    cell = 2 * rmax
    grid = {}
    for i, p in enumerate(x):
        grid.setdefault(tuple(int(math.floor(p[d] / cell)) for d in range(3)), []).append(i)
    # Halton points (bases 2, 3, 5): the same deterministic set for both codes.
    def halton(i, b):
        f, v = 1.0, 0.0
        while i > 0:
            f /= b
            v += f * (i % b)
            i //= b
        return v
    inside = 0
    for k in range(1, npts + 1):
        q = (lo[0] + halton(k, 2) * (hi[0] - lo[0]), lo[1] + halton(k, 3) * (hi[1] - lo[1]),
             lo[2] + halton(k, 5) * (hi[2] - lo[2]))
        c = tuple(int(math.floor(q[d] / cell)) for d in range(3))
        hit = False
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in grid.get((c[0] + dx, c[1] + dy, c[2] + dz), ()):
                        p = x[j]
                        if (q[0] - p[0]) ** 2 + (q[1] - p[1]) ** 2 + (q[2] - p[2]) ** 2 < r[j] * r[j]:
                            hit = True
                            break
                    if hit:
                        break
                if hit:
                    break
            if hit:
                break
        inside += hit
    phi = inside / npts
    return phi, math.sqrt(phi * (1 - phi) / npts), surface, len(x)


def main():
    kind, path = sys.argv[1], sys.argv[2]
    x, r = read_vtu(path) if kind == "grains" else read_dump(path)
    phi, err, surface, n = bulk_fraction(x, r)
    print("%.4f %.4f %.5f %d" % (phi, err, surface, n))


if __name__ == "__main__":
    main()
