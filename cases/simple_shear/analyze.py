#!/usr/bin/env python3
"""mu(I) and phi(I) from the simple_shear sweep (run.sh).

analyze.py OUT [PNG]: reads OUT/I_*/stress.csv (the whole cell, contact +
kinetic stress) and OUT/I_*/rate.txt, averages the rows from the run's
average_after on (summary.json), and writes OUT/mu_I.csv and, with
matplotlib, PNG. Per point: mu = -<s_xy>/<s_yy> (compressive > 0, so s_xy < 0
for du_x/dy > 0), I = rate d / sqrt(<s_yy>/rho) with the measured pressure,
phi = <solid fraction>; the error bars are the spread of five consecutive
blocks of the averaged rows (standard error of their means). Fits:
mu(I) = mu_s + (mu_2 - mu_s) / (1 + I_0/I) (Jop, Forterre & Pouliquen 2006;
least squares, I_0 on a fine logarithmic grid) and phi(I) = phi_c - b I.
Prints the fitted values; exits 1 when there are no points.
"""
import csv
import glob
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from run_summary import stress_summary  # noqa: E402

RHO, D = 2500.0, 0.001  # the case's grain density and mean diameter


def point(folder):
    with open(os.path.join(folder, "summary.json")) as f:
        summary = json.load(f)
    after = stress_summary(summary)["average_after_s"]
    with open(os.path.join(folder, "rate.txt")) as f:
        rate = float(f.read().split()[0])
    rows = []
    with open(os.path.join(folder, "stress.csv")) as f:
        for r in csv.DictReader(f):
            if float(r["time_s"]) >= after:
                rows.append((float(r["sxy_Pa"]), float(r["syy_Pa"]), float(r["solid_fraction"])))
    if len(rows) < 10:
        return None

    def means(rs):
        n = len(rs)
        sxy = sum(r[0] for r in rs) / n
        syy = sum(r[1] for r in rs) / n
        return -sxy / syy, syy, sum(r[2] for r in rs) / n

    mu, p, phi = means(rows)
    k = len(rows) // 5
    blocks = [means(rows[i * k:(i + 1) * k]) for i in range(5)]

    def sem(j):
        m = sum(b[j] for b in blocks) / 5
        return math.sqrt(sum((b[j] - m) ** 2 for b in blocks) / 4 / 5)

    inertial = rate * D / math.sqrt(p / RHO)
    return {"I": inertial, "rate": rate, "mu": mu, "mu_err": sem(0), "phi": phi, "phi_err": sem(2), "p": p}


def fit_mu(pts):
    best = None
    for k in range(401):
        i0 = 10 ** (-4 + 5 * k / 400)  # 1e-4 ... 10
        xs = [1 / (1 + i0 / q["I"]) for q in pts]
        ys = [q["mu"] for q in pts]
        n = len(xs)
        mx, my = sum(xs) / n, sum(ys) / n
        sxx = sum((x - mx) ** 2 for x in xs)
        if sxx == 0:
            continue
        slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
        mu_s = my - slope * mx
        res = sum((mu_s + slope * x - y) ** 2 for x, y in zip(xs, ys))
        if best is None or res < best[0]:
            best = (res, mu_s, mu_s + slope, i0)
    return best[1:]


def fit_line(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return my - slope * mx, -slope


def main():
    if len(sys.argv) < 2:
        sys.exit("usage: analyze.py OUT [PNG]")
    out = sys.argv[1]
    pts = []
    for folder in sorted(glob.glob(os.path.join(out, "I_*"))):
        if os.path.exists(os.path.join(folder, "summary.json")):
            q = point(folder)
            if q:
                pts.append(q)
    if not pts:
        print("analyze.py: no finished points in " + out, file=sys.stderr)
        sys.exit(1)
    pts.sort(key=lambda q: q["I"])
    with open(os.path.join(out, "mu_I.csv"), "w") as f:
        f.write("I,rate_per_s,mu,mu_err,solid_fraction,solid_fraction_err,pressure_Pa\n")
        for q in pts:
            f.write("%.6g,%.6g,%.6g,%.3g,%.6g,%.3g,%.6g\n" % (q["I"], q["rate"], q["mu"], q["mu_err"], q["phi"],
                                                           q["phi_err"], q["p"]))
    for q in pts:
        print("I = %.4g  mu = %.4f +- %.4f  phi = %.4f +- %.4f  p = %.1f Pa" % (q["I"], q["mu"], q["mu_err"], q["phi"],
                                                                            q["phi_err"], q["p"]))
    fit = {}
    if len(pts) >= 3:
        mu_s, mu_2, i0 = fit_mu(pts)
        phi_c, b = fit_line([q["I"] for q in pts], [q["phi"] for q in pts])
        fit = {"mu_s": mu_s, "mu_2": mu_2, "I_0": i0, "phi_c": phi_c, "b": b}
        print("fit: mu_s = %.4f, mu_2 = %.4f, I_0 = %.4f; phi_c = %.4f, b = %.4f" % (mu_s, mu_2, i0, phi_c, b))
        with open(os.path.join(out, "fit.json"), "w") as f:
            json.dump(fit, f, indent=1)
    if len(sys.argv) > 2:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("analyze.py: no matplotlib, no picture", file=sys.stderr)
            return
        fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
        I = [q["I"] for q in pts]
        ax[0].errorbar(I, [q["mu"] for q in pts], yerr=[q["mu_err"] for q in pts], fmt="o", label="grains")
        ax[1].errorbar(I, [q["phi"] for q in pts], yerr=[q["phi_err"] for q in pts], fmt="o", label="grains")
        if fit:
            xs = [10 ** (-3.2 + 2.9 * k / 100) for k in range(101)]  # 6e-4 ... 0.5
            ax[0].plot(xs, [fit["mu_s"] + (fit["mu_2"] - fit["mu_s"]) / (1 + fit["I_0"] / x) for x in xs], "-",
                       label="mu_s %.3f, mu_2 %.3f, I_0 %.3f" % (fit["mu_s"], fit["mu_2"], fit["I_0"]))
            # Jop, Forterre & Pouliquen 2006 (Nature 441, 727): glass beads, experiment.
            ax[0].plot(xs, [0.38 + 0.26 / (1 + 0.279 / x) for x in xs], "--", color="gray",
                       label="Jop et al. 2006 (glass beads, experiment)")
            ax[1].plot(xs, [fit["phi_c"] - fit["b"] * x for x in xs], "-",
                       label="phi_c %.3f, b %.3f" % (fit["phi_c"], fit["b"]))
        for a, name in zip(ax, ["mu = -s_xy / s_yy", "solid fraction"]):
            a.set_xscale("log")
            a.set_xlabel("inertial number I")
            a.set_ylabel(name)
            a.legend(fontsize=8)
        fig.suptitle("simple shear at P = 1000 Pa, 1000 spheres, friction 0.5")
        fig.tight_layout()
        fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
