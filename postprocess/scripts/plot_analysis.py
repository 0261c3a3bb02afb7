#!/usr/bin/env python3
"""PNG plots of a `grains analyze` folder.

usage: python3 plot_analysis.py ANALYSIS_DIR

Reads analysis.json, phi_profile.csv, rdf.csv, coordination.csv and
contact_forces.csv (those present) and writes phi_profile.png, rdf.png,
coordination.png and contact_forces.png next to them. Exit status 3 when
matplotlib is missing (Debian: python3-matplotlib), 2 for a bad folder.
"""
import csv
import json
import os
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.stderr.write("plot_analysis.py: matplotlib is not installed (Debian: python3-matplotlib)\n")
    sys.exit(3)


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in (rows[0].keys() if rows else [])}


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    print("wrote", path)


def main(d):
    meta_path = os.path.join(d, "analysis.json")
    if not os.path.isfile(meta_path):
        sys.stderr.write("plot_analysis.py: %s has no analysis.json\n" % d)
        return 2
    with open(meta_path) as f:
        meta = json.load(f)
    dmean = meta.get("mean_diameter", 1.0) or 1.0
    region = meta["region"]
    frame = "frame %d, t = %.4g s" % (meta["frame"], meta["time"])

    p = os.path.join(d, "phi_profile.csv")
    if os.path.isfile(p):
        t = read_csv(p)
        if t:
            ax_name = [k for k in t if k.endswith("_lo")][0][0]
            axis = "xyz".index(ax_name)
            mid = [0.5 * (a + b) / dmean for a, b in zip(t[ax_name + "_lo"], t[ax_name + "_hi"])]
            fig, ax = plt.subplots(figsize=(4.5, 5.5))
            ax.errorbar(t["phi"], mid, xerr=t["phi_error"] if any(t["phi_error"]) else None, fmt="-o", ms=2.5, lw=1)
            lo, hi = region["min"][axis] / dmean, region["max"][axis] / dmean
            ax.axhspan(lo, hi, color="0.85", zorder=0, label="analysis region")
            phi = meta["packing_fraction"]
            ax.axvline(phi["value"], color="C3", lw=1, ls="--", label="region: %.4f" % phi["value"])
            ax.set_xlabel(r"packing fraction $\phi$")
            ax.set_ylabel("%s / d" % ax_name)
            ax.set_xlim(0, max(0.8, max(t["phi"]) * 1.05))
            ax.set_title(frame, fontsize=9)
            ax.legend(fontsize=8, loc="best")
            save(fig, os.path.join(d, "phi_profile.png"))

    p = os.path.join(d, "rdf.csv")
    if os.path.isfile(p):
        t = read_csv(p)
        if t:
            fig, ax = plt.subplots(figsize=(6, 4))
            ax.plot(t["r_over_d"], t["g"], lw=1)
            ax.axhline(1.0, color="0.6", lw=0.8, ls=":")
            ax.set_xlabel("r / d")
            ax.set_ylabel("g(r)")
            ax.set_title("radial distribution, " + frame, fontsize=9)
            save(fig, os.path.join(d, "rdf.png"))

    p = os.path.join(d, "coordination.csv")
    if os.path.isfile(p):
        t = read_csv(p)
        if t:
            c = meta["coordination"]
            fig, ax = plt.subplots(figsize=(5, 4))
            ax.bar(t["z"], t["fraction"], width=0.8)
            ax.set_xlabel("contacts per particle z")
            ax.set_ylabel("fraction of particles")
            ax.set_title("Z = %.3f, without rattlers %.3f, rattlers %.1f %%"
                         % (c["mean"], c["mean_without_rattlers"], 100 * c["rattler_fraction"]), fontsize=9)
            save(fig, os.path.join(d, "coordination.png"))

    p = os.path.join(d, "contact_forces.csv")
    if os.path.isfile(p):
        t = read_csv(p)
        if t and meta["contact_forces"]["contacts"] > 0:
            fig, axs = plt.subplots(1, 2, figsize=(9, 3.8))
            for ax, log in zip(axs, (False, True)):
                xs = [x for x, y in zip(t["f_over_mean"], t["pdf"]) if not log or y > 0]
                ys = [y for y in t["pdf"] if not log or y > 0]
                ax.plot(xs, ys, "-o", ms=2.5, lw=1)
                ax.set_xlabel(r"$f_n / \langle f_n \rangle$ (Hertz, from overlaps)")
                ax.set_ylabel("P")
                if log:
                    ax.set_yscale("log")
            axs[0].set_title("%d contacts, %s" % (meta["contact_forces"]["contacts"], frame), fontsize=9)
            save(fig, os.path.join(d, "contact_forces.png"))
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
