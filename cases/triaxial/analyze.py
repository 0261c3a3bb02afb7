#!/usr/bin/env python3
"""Triaxial test analysis: from the shear stage's wall_loads.csv, the axial
stress sigma_1 (top wall), the confining stress sigma_3 (mean of the four
side walls), the axial strain eps_a = 1 - H/H0 and the volumetric strain
eps_v = 1 - V/V0 of the box the walls bound; the mobilised friction angle
sin(phi) = (sigma_1 - sigma_3) / (sigma_1 + sigma_3), its peak and its mean
over the last quarter of the strain (the critical state, when the volume
has stopped changing). Writes triaxial.csv beside wall_loads.csv and a plot.

    python3 analyze.py OUT/shear [triaxial.png]
"""
import csv
import math
import os
import sys


def main():
    out = sys.argv[1]
    png = sys.argv[2] if len(sys.argv) > 2 else os.path.join(out, "triaxial.png")
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
    dil = (last[-1][2] - last[0][2]) / (last[-1][1] - last[0][1]) if last[-1][1] > last[0][1] else 0.0
    print("axial strain reached: %.3f" % table[-1][1])
    print("peak friction angle: %.1f deg at axial strain %.3f (sigma1/sigma3 = %.2f)" %
          (peak[5], peak[1], peak[3] / peak[4]))
    print("critical-state friction angle (last quarter of the strain): %.1f deg" % crit)
    print("volumetric strain rate over that quarter: d eps_v / d eps_a = %.3f (0 at the critical state)" % dil)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(no matplotlib: no plot)")
        return
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
    ax[0].plot([t[1] for t in table], [t[5] for t in table])
    ax[0].axhline(crit, ls="--", c="gray", label="critical state %.1f°" % crit)
    ax[0].set_xlabel("axial strain")
    ax[0].set_ylabel("mobilised friction angle (deg)")
    ax[0].legend()
    ax[1].plot([t[1] for t in table], [t[2] for t in table])
    ax[1].set_xlabel("axial strain")
    ax[1].set_ylabel("volumetric strain (compression > 0)")
    fig.suptitle("grains: drained triaxial test, 1500 spheres, μ = 0.5, σ3 = 20 kPa")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    print("wrote", png)


if __name__ == "__main__":
    main()
