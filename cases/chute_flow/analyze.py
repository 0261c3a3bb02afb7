#!/usr/bin/env python3
"""The chute flow's steady profiles (cases/chute_flow/run.sh).

analyze.py RUN ANGLE [PNG] [--check]: reads RUN/profile_mean.csv (bins of one diameter
along z from the top of the base, z = 0.5, averaged from average_after on)
and RUN/stress.csv, and checks, in units of d, m and g:
  - the bulk: bins at least 3 d above the base and 3 d below the surface;
    their solid fraction's mean and spread (depth independence);
  - the flow height h = the solid volume per area / the bulk solid fraction;
  - the Bagnold profile v_x(z) = a [h^(3/2) - (h - z)^(3/2)] (Silbert et al.
    2001, z from the base), a by least squares over the bulk bins with the
    base velocity subtracted: its largest deviation relative to the surface
    velocity, and R^2;
  - the momentum balance: sigma_zz(z) against the weight of the grains above
    (phi g cos(angle) integrated), and sigma_xz / sigma_zz = tan(angle) in
    the bulk;
  - steadiness: the mean velocity over the two halves of the averaging window.
Writes RUN/chute_flow.json; prints the figures; PNG with matplotlib. With
--check, exits 1 unless the flow is steady (the halves' mean velocities
within 3 %), the bulk's solid fraction depth-independent (every bulk bin
within 0.01 of the mean), sigma_xz / sigma_zz = tan(angle) to 3 % and
sigma_zz the weight above to 5 % in the bulk, and the Bagnold fit holds to
R^2 >= 0.95 with no bulk bin off by more than 8 % of the surface velocity
(a flow 15 d deep is measurably straighter than Bagnold's: README.md).
"""
import csv
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from run_summary import stress_summary  # noqa: E402


def read(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def main():
    run, angle = sys.argv[1], float(sys.argv[2])
    th = math.radians(angle)
    with open(os.path.join(run, "summary.json")) as f:
        after = stress_summary(json.load(f))["average_after_s"]
    prof = read(os.path.join(run, "profile_mean.csv"))
    z0 = 0.5  # the top of the base (its centres at z = 0, radius 0.5); bins start there
    z = [r["position_m"] - z0 for r in prof]  # bin centres above the base
    phi = [r["solid_fraction"] for r in prof]
    vx = [r["vx_mps"] for r in prof]
    width = z[1] - z[0]
    filled = [i for i in range(len(z)) if phi[i] > 0.05]
    top = max(filled)
    # Bulk: 3 d clear of the base and of the surface (the last bin above half the largest phi).
    half = max(phi) / 2
    surface = max(i for i in range(len(z)) if phi[i] > half)
    bulk = [i for i in range(len(z)) if z[i] >= 3 and z[i] <= z[surface] - 3]
    phi_bulk = sum(phi[i] for i in bulk) / len(bulk)
    phi_spread = max(abs(phi[i] - phi_bulk) for i in bulk)
    h = sum(phi[i] * width for i in range(top + 1)) / phi_bulk
    # Bagnold fit over the bulk, relative to the slip velocity at the base.
    v0 = vx[0]
    xs = [h ** 1.5 - max(h - z[i], 0) ** 1.5 for i in bulk]
    ys = [vx[i] - v0 for i in bulk]
    a = sum(x * y for x, y in zip(xs, ys)) / sum(x * x for x in xs)
    vs = max(vx[i] for i in bulk)
    dev = max(abs(a * x - y) for x, y in zip(xs, ys)) / vs
    my = sum(ys) / len(ys)
    r2 = 1 - sum((a * x - y) ** 2 for x, y in zip(xs, ys)) / sum((y - my) ** 2 for y in ys)
    # Momentum balance: sigma_zz averaged over bin k (the method of planes
    # through the bin) = the weight of the grains whose centres lie above
    # the plane, averaged over the bin: those of the bins above, and half of
    # bin k's own (density 1, d 1, g 1).
    st_rows = read(os.path.join(run, "stress.csv"))
    area = st_rows[0]["volume_m3"] / (len(z) * width)
    count = [r["grains"] for r in prof]
    szz, sxz = [r["szz_Pa"] for r in prof], [r["sxz_Pa"] for r in prof]
    weight = [(0.5 * count[k] + sum(count[k + 1:])) * math.pi / 6 * math.cos(th) / area for k in range(len(z))]
    bal = max(abs(szz[k] - weight[k]) / weight[k] for k in bulk)
    mu = [abs(sxz[k]) / szz[k] for k in bulk]
    mu_mean = sum(mu) / len(mu)
    # Steadiness: mean vx of the whole cell, first and second half of the window.
    st = [r for r in st_rows if r["time_s"] >= after]
    n = len(st) // 2
    v1 = sum(r["vx_mps"] for r in st[:n]) / n
    v2 = sum(r["vx_mps"] for r in st[n:2 * n]) / n
    res = {"angle_deg": angle, "bulk_bins": len(bulk), "phi_bulk": phi_bulk, "phi_bulk_max_deviation": phi_spread,
           "flow_height_d": h, "bagnold_a": a, "slip_velocity": v0, "surface_velocity": vs,
           "bagnold_max_deviation_rel_surface": dev, "bagnold_r2": r2,
           "sigma_zz_vs_weight_max_rel": bal, "mu_bulk": mu_mean, "tan_angle": math.tan(th),
           "mean_vx_first_half": v1, "mean_vx_second_half": v2}
    with open(os.path.join(run, "chute_flow.json"), "w") as f:
        json.dump(res, f, indent=1)
    for k, v in res.items():
        print("%-36s %.6g" % (k, v))
    if "--check" in sys.argv:
        bad = []
        if abs(v2 - v1) > 0.03 * abs(v2):
            bad.append("not steady")
        if phi_spread > 0.01:
            bad.append("solid fraction varies with depth")
        if r2 < 0.95 or dev > 0.08:
            bad.append("not the Bagnold profile")
        if bal > 0.05:
            bad.append("sigma_zz is not the weight above")
        if abs(mu_mean / math.tan(th) - 1) > 0.03:
            bad.append("sigma_xz / sigma_zz is not tan(angle)")
        print("check: " + (", ".join(bad) if bad else "all met"))
        if bad:
            sys.exit(1)
    args = [a for a in sys.argv[1:] if a != "--check"]
    if len(args) > 2:
        try:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            return
        fig, ax = plt.subplots(1, 3, figsize=(11, 3.8), sharey=True)
        ax[0].plot(vx[:top + 1], z[:top + 1], "o", ms=4, label="grains")
        zz = [h * k / 100 for k in range(101)]
        ax[0].plot([v0 + a * (h ** 1.5 - (h - q) ** 1.5) for q in zz], zz, "-",
                   label="Bagnold, a = %.3f, h = %.1f d" % (a, h))
        ax[0].set_xlabel("v_x / sqrt(g d)")
        ax[0].set_ylabel("z / d above the base")
        ax[1].plot(phi[:top + 1], z[:top + 1], "o", ms=4)
        ax[1].axvline(phi_bulk, color="gray", lw=0.8)
        ax[1].set_xlabel("solid fraction (bulk %.3f)" % phi_bulk)
        ax[2].plot(szz[:top + 1], z[:top + 1], "o", ms=4, label="sigma_zz")
        ax[2].plot(weight[:top + 1], z[:top + 1], "-", label="weight above")
        ax[2].plot([abs(s) for s in sxz[:top + 1]], z[:top + 1], "s", ms=3, label="|sigma_xz|")
        ax[2].set_xlabel("stress / (m g / d^2)")
        for a_ in (ax[0], ax[2]):
            a_.legend(fontsize=8)
        fig.suptitle("chute flow at %g degrees, rough frozen base (Silbert et al. 2001 physics)" % angle)
        fig.tight_layout()
        fig.savefig(args[2], dpi=110)


if __name__ == "__main__":
    main()
