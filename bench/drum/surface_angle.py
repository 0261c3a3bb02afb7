#!/usr/bin/env python3
"""Dynamic angle of repose of the free surface of a drum bed, the method of
`grains repose` (postprocess/surface_angle.cpp) re-implemented in Python so
that LIGGGHTS's dumps are measured exactly as grains's frames (bench/drum).

  surface_angle.py liggghts DIR --dt DT [options]
      DIR holds LIGGGHTS 'dump custom ... id x y z radius' files, one frame
      each (any name; the time is ITEM: TIMESTEP x DT)
  surface_angle.py grains OUTDIR [options]
      grains's own frames (OUTDIR/particles.pvd and its .vtu files, read with
      bench/pour/packing.py), to check this script against `grains repose`
  surface_angle.py compare MINE.csv REPOSE.csv [--tol DEG]
      per-frame angles of two repose.csv files, matched by time (1e-6 s):
      max |difference|; exit status 1 above --tol (default 0.01 deg)

  options (as grains repose):
    --axis x|y       drum axis (default y); u = the other horizontal coordinate, v = z
    --centre X,Y,Z   a point on the axis (default 0,0,0)
    --radius R       drum radius R (default: in each frame, the farthest particle
                     edge from the axis, hypot(u - u_c, z - z_c) + radius)
    --column W       column width (default: 2 mean diameters of the first frame measured)
    --span F         columns over |u - u_c| <= F R (default 0.6)
    --from T, --to T time window, s (frames with T_from <= t <= T_to)
    -o DIR           writes DIR/repose.csv (grains's columns, plus the bed's mean
                     x and z of the centres) and DIR/repose.json (the summary)

Per frame: columns k = floor((u - u_c) / W) for |u - u_c| <= F R (k clamped
to [floor(-F R / W), floor(F R / W)]); a column's top is its highest particle,
z + radius (the first one in file order on a tie), at that particle's u; a
least-squares line v = a u + b through the tops (about their means); the angle
is atan|a| in degrees. A frame with fewer than 4 columns holding particles is
skipped. Summary: mean, sample standard deviation (n - 1), standard error
std / sqrt(n) (frames are correlated, so a lower bound).
"""
import json
import math
import os
import re
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "pour"))

MIN_COLUMNS = 4


class Refused(Exception):
    pass


def surface_angle(x, r, axis, centre, column, radius, span):
    """One frame: dict of time-independent results (see the module doc)."""
    iu = 1 if axis == 0 else 0
    uc, vc = centre[iu], centre[2]
    if not x:
        raise Refused("no particles")
    R = radius
    if R <= 0:
        R = 0.0
        for q, s in zip(x, r):
            R = max(R, math.hypot(q[iu] - uc, q[2] - vc) + s)
    half = span * R
    k_lo, k_hi = math.floor(-half / column), math.floor(half / column)
    top = {}
    for q, s in zip(x, r):
        du = q[iu] - uc
        if abs(du) > half:
            continue
        k = min(max(math.floor(du / column), k_lo), k_hi)
        h = q[2] + s
        if k not in top or h > top[k][0]:
            top[k] = (h, q[iu])
    cols = [top[k] for k in sorted(top)]
    if len(cols) < MIN_COLUMNS:
        raise Refused("only %d column(s) hold particles" % len(cols))
    u = [c[1] for c in cols]
    v = [c[0] for c in cols]
    n = float(len(cols))
    mu, mv = sum(u) / n, sum(v) / n
    suu = sum((a - mu) ** 2 for a in u)
    suv = sum((a - mu) * (b - mv) for a, b in zip(u, v))
    slope = suv / suu
    icpt = mv - slope * mu
    rms = math.sqrt(sum((b - (slope * a + icpt)) ** 2 for a, b in zip(u, v)) / n)
    return {"angle_deg": math.degrees(math.atan(abs(slope))), "slope": slope, "columns": len(cols),
            "rms_residual": rms, "radius": R,
            "bed_x": sum(q[0] for q in x) / len(x), "bed_z": sum(q[2] for q in x) / len(x)}


def liggghts_frames(d, dt):
    """[(time, path)] of the dump files in d, by timestep."""
    out = []
    for name in os.listdir(d):
        p = os.path.join(d, name)
        if not os.path.isfile(p):
            continue
        with open(p) as f:
            if f.readline().strip() != "ITEM: TIMESTEP":
                continue
            out.append((int(f.readline()) * dt, p))
    return sorted(out)


def read_dump(path):
    lines = open(path).read().splitlines()
    k = [i for i, s in enumerate(lines) if s.startswith("ITEM: ATOMS")]
    if len(k) != 1:
        sys.exit("surface_angle.py: %s: expected one frame (ITEM: ATOMS once)" % path)
    cols = lines[k[0]].split()[2:]
    ix, iy, iz, ir = (cols.index(c) for c in ("x", "y", "z", "radius"))
    x, r = [], []
    for s in lines[k[0] + 1:]:
        f = s.split()
        if len(f) < len(cols):
            continue
        x.append((float(f[ix]), float(f[iy]), float(f[iz])))
        r.append(float(f[ir]))
    return x, r


def grains_frames(outdir):
    """[(time, path)] of OUTDIR/particles.pvd, in file order."""
    text = open(os.path.join(outdir, "particles.pvd")).read()
    out = []
    for tag in re.findall(r"<DataSet[^>]*>", text):
        a = dict(re.findall(r'(\w+)="([^"]*)"', tag))
        out.append((float(a["timestep"]), os.path.join(outdir, a["file"])))
    return out


def measure(kind, src, o):
    import packing  # bench/pour: the VTU reader
    frames = liggghts_frames(src, o["dt"]) if kind == "liggghts" else grains_frames(src)
    chosen = [(t, p) for t, p in frames if t >= o["from"] and (o["to"] is None or t <= o["to"])]
    if not chosen:
        sys.exit("surface_angle.py: no frame of %s in [%g, %s] s (%d frames)" % (src, o["from"], o["to"], len(frames)))
    reader = read_dump if kind == "liggghts" else packing.read_vtu
    column = o["column"]
    rows, skipped = [], 0
    for t, p in chosen:
        x, r = reader(p)
        if column <= 0:  # one width for the series: 2 mean diameters of the first frame
            column = 2 * (sum(2 * s for s in r) / len(r))
        try:
            res = surface_angle(x, r, o["axis"], o["centre"], column, o["radius"], o["span"])
        except Refused as e:
            skipped += 1
            print("surface_angle.py: skipped the frame at t = %g s: %s" % (t, e), file=sys.stderr)
            continue
        res["time"], res["file"] = t, p
        rows.append(res)
    if not rows:
        sys.exit("surface_angle.py: no frame could be measured")
    n = len(rows)
    a = [q["angle_deg"] for q in rows]
    mean = sum(a) / n
    std = math.sqrt(sum((v - mean) ** 2 for v in a) / (n - 1)) if n > 1 else 0.0
    plus = sum(q["slope"] > 0 for q in rows)
    u = "y" if o["axis"] == 0 else "x"
    summary = {
        "frames": n, "mean_deg": mean, "std_deg": std, "standard_error_deg": std / math.sqrt(n),
        "from_s": min(q["time"] for q in rows), "to_s": max(q["time"] for q in rows),
        "axis": "xy"[o["axis"]], "column_m": column, "span": o["span"],
        "radius_m": o["radius"] if o["radius"] > 0 else sum(q["radius"] for q in rows) / n,
        "centre": list(o["centre"]),
        "radius_source": "--radius" if o["radius"] > 0 else "each frame: the farthest particle edge from the axis",
        "higher_side": ("+" if plus == n else "-" if plus == 0 else "mixed ") + u,
        "frames_skipped": skipped, "source": kind,
        "last_frame": {"time_s": rows[-1]["time"], "bed_x_m": rows[-1]["bed_x"], "bed_z_m": rows[-1]["bed_z"],
                       "particles": len(reader(rows[-1]["file"])[0])},
    }
    if o["out"]:
        os.makedirs(o["out"], exist_ok=True)
        with open(os.path.join(o["out"], "repose.csv"), "w") as f:
            f.write("time_s,angle_deg,slope,columns,rms_residual_m,radius_m,bed_x_m,bed_z_m\n")
            for q in rows:
                f.write("%.10g,%.10g,%.10g,%d,%.10g,%.10g,%.10g,%.10g\n" % (
                    q["time"], q["angle_deg"], q["slope"], q["columns"], q["rms_residual"], q["radius"],
                    q["bed_x"], q["bed_z"]))
        with open(os.path.join(o["out"], "repose.json"), "w") as f:
            json.dump(summary, f, indent=2)
            f.write("\n")
    print("angle of repose %.2f ± %.2f deg (SE %.2f; %d frames, t = %.4g .. %.4g s%s; higher on the %s side; "
          "column %g m, span %g, radius %s, centre %s)%s" % (
              mean, std, std / math.sqrt(n), n, summary["from_s"], summary["to_s"],
              ", %d skipped" % skipped if skipped else "", summary["higher_side"], column, o["span"],
              "%g m" % o["radius"] if o["radius"] > 0 else "per frame (mean %.5g m)" % summary["radius_m"],
              ",".join("%g" % c for c in o["centre"]), " -> " + o["out"] if o["out"] else ""))


def read_csv(path):
    lines = open(path).read().split()
    head = lines[0].split(",")
    it, ia = head.index("time_s"), head.index("angle_deg")
    return [(float(s.split(",")[it]), float(s.split(",")[ia])) for s in lines[1:]]


def compare(mine, ref, tol):
    a, b = read_csv(mine), read_csv(ref)
    worst, matched = 0.0, 0
    for t, v in b:
        m = [w for s, w in a if abs(s - t) <= 1e-6]
        if len(m) != 1:
            print("compare: the frame at t = %g s of %s is not in %s" % (t, ref, mine))
            return 1
        worst = max(worst, abs(m[0] - v))
        matched += 1
    if len(a) != len(b):
        print("compare: %d frames in %s, %d in %s" % (len(a), mine, len(b), ref))
        return 1
    ok = worst <= tol
    print("compare: %d frames, max |angle difference| %.3g deg (%s %g deg)" % (matched, worst, "<=" if ok else ">", tol))
    return 0 if ok else 1


def main(argv):
    if len(argv) < 3 or argv[1] not in ("liggghts", "grains", "compare"):
        sys.exit(__doc__)
    if argv[1] == "compare":
        tol = float(argv[argv.index("--tol") + 1]) if "--tol" in argv else 0.01
        return compare(argv[2], argv[3], tol)
    o = {"axis": 1, "centre": (0.0, 0.0, 0.0), "radius": 0.0, "column": 0.0, "span": 0.6, "from": 0.0,
         "to": None, "out": None, "dt": None}
    i = 3
    while i < len(argv):
        k, v = argv[i], argv[i + 1] if i + 1 < len(argv) else None
        if v is None:
            sys.exit("surface_angle.py: %s needs a value" % k)
        if k == "--axis":
            if v not in ("x", "y"):
                sys.exit("surface_angle.py: --axis x or y (gravity along -z)")
            o["axis"] = "xy".index(v)
        elif k == "--centre":
            o["centre"] = tuple(float(c) for c in v.split(","))
        elif k in ("--radius", "--column", "--span", "--from", "--to", "--dt"):
            o[k[2:]] = float(v)
        elif k == "-o":
            o["out"] = v
        else:
            sys.exit("surface_angle.py: unknown option %s" % k)
        i += 2
    if argv[1] == "liggghts" and not o["dt"]:
        sys.exit("surface_angle.py: liggghts needs --dt (time = timestep x dt)")
    if not (0 < o["span"] <= 1) or len(o["centre"]) != 3:
        sys.exit("surface_angle.py: bad --span or --centre")
    measure(argv[1], argv[2], o)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
