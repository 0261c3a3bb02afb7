#!/usr/bin/env python3
"""Triaxial test analysis: from the shear stage's wall_loads.csv, the axial
stress sigma_1 (top wall), the confining stress sigma_3 (mean of the four
side walls), the axial strain eps_a = 1 - H/H0 and the volumetric strain
eps_v = 1 - V/V0 of the box the walls bound; the mobilised friction angle
sin(phi) = (sigma_1 - sigma_3) / (sigma_1 + sigma_3), its peak and its mean
over the last quarter of the strain (the critical state, when the volume
has stopped changing). Writes triaxial.csv and triaxial.json (the peak,
the critical state, the dilatancy at the peak and over the last quarter)
beside wall_loads.csv, and a plot; further runs given as LABEL=DIR (their
shear stage) are drawn beside it, each from its own triaxial.csv; LABEL
(environment) names this run.

    python3 analyze.py OUT/shear [triaxial.png] [LABEL=OTHER/shear ...]
"""
import json
import csv
import math
import os
import sys


def dilatancy(table, lo, hi):
    """d eps_v / d eps_a by least squares over the rows with lo <= eps_a <= hi."""
    pts = [(t[1], t[2]) for t in table if lo <= t[1] <= hi]
    if len(pts) < 2:
        return 0.0
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx if sxx > 0 else 0.0


def read_csv(out):
    with open(os.path.join(out, "triaxial.csv")) as f:
        return [tuple(float(v) for v in r) for r in list(csv.reader(f))[1:]]


def main():
    out = sys.argv[1]
    png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(out, "triaxial.png")
    others = [a.rsplit("=", 1) for a in sys.argv[3:]]  # LABEL=DIR (the label may hold "=")
    rows = {}
    with open(os.path.join(out, "wall_loads.csv")) as f:
        for r in csv.DictReader(f):
            rows.setdefault(int(r["step"]), {})[r["name"]] = r
    steps = sorted(s for s in rows if len(rows[s]) == 6)
    if not steps:
        sys.exit("no complete rows in wall_loads.csv")

    def box(w):
        lx = float(w["x1"]["px_m"]) - float(w["x0"]["px_m"])
        ly = float(w["y1"]["py_m"]) - float(w["y0"]["py_m"])
        h = float(w["top"]["pz_m"]) - float(w["bottom"]["pz_m"])
        return lx, ly, h

    lx0, ly0, h0 = box(rows[steps[0]])
    table = []
    for s in steps:
        w = rows[s]
        lx, ly, h = box(w)
        s1 = float(w["top"]["stress_Pa"])
        s3 = sum(float(w[k]["stress_Pa"]) for k in ("x0", "x1", "y0", "y1")) / 4
        ea = 1 - h / h0
        ev = 1 - (lx * ly * h) / (lx0 * ly0 * h0)
        phi = math.degrees(math.asin((s1 - s3) / (s1 + s3))) if s1 + s3 > 0 else 0.0
        table.append((float(w["top"]["time_s"]), ea, ev, s1, s3, phi))
    with open(os.path.join(out, "triaxial.csv"), "w") as f:
        f.write("time_s,axial_strain,volumetric_strain,sigma1_Pa,sigma3_Pa,friction_angle_deg\n")
        for t in table:
            f.write(",".join("%.8g" % v for v in t) + "\n")
    peak = max(table, key=lambda t: t[5])
    last = [t for t in table if t[1] >= 0.75 * table[-1][1]]
    crit = sum(t[5] for t in last) / len(last)
    dil = dilatancy(table, last[0][1], last[-1][1])
    # Dilatancy about the peak: a line through +-2 % of axial strain around it
    # (dense: dilating, < 0; loose: contracting, > 0).
    dil_peak = dilatancy(table, peak[1] - 0.02, peak[1] + 0.02)
    with open(os.path.join(out, "triaxial.json"), "w") as f:
        json.dump({"axial_strain_reached": table[-1][1],
                   "peak_friction_angle_deg": peak[5], "peak_axial_strain": peak[1],
                   "peak_stress_ratio": peak[3] / peak[4],
                   "critical_friction_angle_deg": crit,
                   "critical_friction_angle_spread_deg": max(t[5] for t in last) - min(t[5] for t in last),
                   "dilatancy_at_peak": dil_peak, "dilatancy_last_quarter": dil,
                   "volumetric_strain_end": table[-1][2]}, f, indent=1)
    print("axial strain reached: %.3f" % table[-1][1])
    print("peak friction angle: %.1f deg at axial strain %.3f (sigma1/sigma3 = %.2f)" %
          (peak[5], peak[1], peak[3] / peak[4]))
    print("critical-state friction angle (last quarter of the strain): %.1f deg" % crit)
    print("volumetric strain rate over that quarter: d eps_v / d eps_a = %.3f (0 at the critical state)" % dil)
    print("volumetric strain rate about the peak: %.3f (< 0: dilating)" % dil_peak)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(no matplotlib: no plot)")
        return
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
    runs = [(os.environ.get("LABEL", "this run"), table)] + [(lab, read_csv(d)) for lab, d in others]
    for lab, tab in runs:
        ax[0].plot([t[1] for t in tab], [t[5] for t in tab], label=lab)
        ax[1].plot([t[1] for t in tab], [t[2] for t in tab], label=lab)
    ax[0].axhline(crit, ls="--", c="gray", label="critical state %.1f°" % crit)
    ax[0].set_xlabel("axial strain")
    ax[0].set_ylabel("mobilised friction angle (deg)")
    ax[0].legend()
    if len(runs) > 1:
        ax[1].legend()
    ax[1].set_xlabel("axial strain")
    ax[1].set_ylabel("volumetric strain (compression > 0)")
    fig.suptitle("grains: drained triaxial test, 1500 spheres, μ = 0.5, σ3 = 20 kPa")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print("wrote", png)


if __name__ == "__main__":
    main()
