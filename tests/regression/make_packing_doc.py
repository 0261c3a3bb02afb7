#!/usr/bin/python3
"""Writes docs/packing.md and its plots (docs/packing/*.png) from the result
records of the packing regression suite (JSON files written by the tests
when GRAINS_RESULTS_DIR is set) and the reference table
tests/regression/packing_references.yaml.

    /usr/bin/python3 tests/regression/make_packing_doc.py RESULTS_DIR

Run by tests/regression/make_packing_doc.sh, which first runs the tests.
Only the numbers the records hold appear in the doc: a measurement that was
not run is listed as "not run".
"""
import datetime
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import yaml  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
DOC = os.path.join(ROOT, "docs", "packing.md")
FIG = os.path.join(ROOT, "docs", "packing")


def load(results, name):
    path = os.path.join(results, name + ".json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


def f3(x, nd=3):
    return "–" if x is None else f"{x:.{nd}f}"


def inside(ref, v):
    if v is None:
        return "–"
    return "yes" if ref["band"][0] <= v <= ref["band"][1] else "**NO**"


def beverloo_curve(C, k, rho_b, D):
    return [C * rho_b * math.sqrt(9.81) * max(x - k * 0.001, 0) ** 2.5 for x in D]


def main():
    results = sys.argv[1]
    refs = yaml.safe_load(open(os.path.join(HERE, "packing_references.yaml")))
    os.makedirs(FIG, exist_ok=True)
    fr_ci, fr_long = load(results, "friction_sweep_ci"), load(results, "friction_sweep_long")
    bv_ci, bv_long = load(results, "beverloo_ci"), load(results, "beverloo_long")
    jam_ci, jam_long = load(results, "jamming_ci"), load(results, "jamming_long")
    ell_ci, ell_sweep = load(results, "ellipsoid_ci"), load(results, "ellipsoid_sweep")
    dim_ci, dim_sweep = load(results, "dimer_ci"), load(results, "dimer_sweep")
    res_ci, res = load(results, "clump_resolution_ci"), load(results, "clump_resolution")
    meta = load(results, "meta") or {}

    def mu_phi(rec, mu):
        if not rec:
            return None
        return rec["phi"][rec["mu"].index(mu)]

    # ------------------------------------------------------------ table
    rows = []

    def row(key, ci, long, ci_text=None, long_text=None):
        r = refs[key]
        rows.append(
            f"| {r['quantity']} | {ci_text or f3(ci)} | {long_text or f3(long)} | {r['reference']} | "
            f"[{r['band'][0]}, {r['band'][1]}] | {inside(r, ci)} / {inside(r, long)} | {r['source']} | `{key}` |"
        )

    row("jamming_phi", jam_ci and jam_ci["phi"], jam_long and jam_long["phi"],
        long_text=jam_long and f"{jam_long['phi']:.4f} ± {jam_long['phi_sd']:.4f} (3 seeds)")
    row("jamming_z", jam_ci and jam_ci["z_rigid"], jam_long and jam_long["z_rigid"],
        long_text=jam_long and f"{jam_long['z_rigid']:.3f} ± {jam_long['z_rigid_sd']:.3f}")
    row("pour_phi_mu0", mu_phi(fr_ci, 0), mu_phi(fr_long, 0))
    row("pour_phi_mu05", mu_phi(fr_ci, 0.5), mu_phi(fr_long, 0.5))
    drop_ci = fr_ci and fr_ci["phi"][0] - fr_ci["phi"][-1]
    drop_long = fr_long and fr_long["phi"][0] - fr_long["phi"][-1]
    row("pour_friction_trend", drop_ci, drop_long)
    row("beverloo_C", bv_ci and bv_ci["C_fixed_k"], bv_long and bv_long["C"],
        ci_text=bv_ci and f"{bv_ci['C_fixed_k']:.3f} (k = 1.5)",
        long_text=bv_long and f"{bv_long['C']:.3f} ± {bv_long['se_C']:.3f}")
    row("beverloo_k", None, bv_long and bv_long["k"],
        ci_text=bv_ci and f"({bv_ci['k']:.2f} ± {bv_ci['se_k']:.2f}, recorded)",
        long_text=bv_long and f"{bv_long['k']:.2f} ± {bv_long['se_k']:.2f}")
    row("beverloo_exponent", bv_ci and bv_ci["exponent"], bv_long and bv_long["exponent"],
        ci_text=bv_ci and f"{bv_ci['exponent']:.2f} ± {bv_ci['se_exponent']:.2f}",
        long_text=bv_long and f"{bv_long['exponent']:.2f} ± {bv_long['se_exponent']:.2f}")
    row("ellipsoid_rise", ell_ci and ell_ci["rise"], ell_sweep and ell_sweep.get("rise_1p5"))
    row("ellipsoid_maximum", None, ell_sweep and ell_sweep["peak_aspect_ratio"], ci_text="(long only)")
    row("dimer_rise", dim_ci and dim_ci["rise"], None, long_text="(CI only)")
    row("dimer_maximum", None, dim_sweep and dim_sweep["peak_aspect_ratio"], ci_text="(long only)")
    row("clump_resolution_first_step", res_ci and res_ci["step"], res and res["change"][0],
        long_text=res and f"({res['change'][0]:.4f}, mean of {len(res['phi_all']) // len(res['grid'])} seeds)")
    row("clump_resolution_effect", None, res and res["largest_change_in_se"], ci_text="(long only)")
    row("clump_resolution_convergence", None, res and res["last_change_in_se"], ci_text="(long only)")

    # ------------------------------------------------------------ plots
    figs = []
    if fr_ci or fr_long:
        plt.figure(figsize=(5.2, 3.6))
        if fr_ci:
            plt.errorbar(fr_ci["mu"], fr_ci["phi"], yerr=[fr_ci["sigma_run"]] * len(fr_ci["mu"]), fmt="o-",
                         capsize=3, label="CI: 3,000 spheres, 1 seed (±1 s.d. of a run)")
        if fr_long:
            plt.errorbar(fr_long["mu"], fr_long["phi"], yerr=fr_long["phi_sd"], fmt="s-", capsize=3,
                         label=f"long: 10,000 spheres, mean of {int(fr_long['seeds'])} seeds")
        b = refs["pour_phi_mu05"]["band"]
        plt.fill_between([0.45, 0.55], [b[0]] * 2, [b[1]] * 2, color="tab:green", alpha=0.2,
                         label="accepted at μ = 0.5")
        plt.axhline(0.639, color="gray", ls="--", lw=0.8)
        plt.text(0.12, 0.6405, "frictionless jammed 0.639", color="gray", fontsize=8)
        plt.axhline(0.55, color="gray", ls=":", lw=0.8)
        plt.text(0.6, 0.551, "random loose packing 0.55", color="gray", fontsize=8)
        plt.xlabel("friction coefficient μ")
        plt.ylabel("bulk packing fraction φ")
        plt.legend(fontsize=7)
        plt.tight_layout()
        plt.savefig(os.path.join(FIG, "friction_sweep.png"), dpi=120)
        plt.close()
        figs.append(("friction_sweep.png", "Poured spheres: bulk packing fraction against friction."))
    if bv_ci or bv_long:
        fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
        for rec, mk, lab in ((bv_ci, "o", "CI: silo 20 d"), (bv_long, "s", "long: silo 26 d")):
            if not rec:
                continue
            D = rec["D"]
            Dd = [x / 0.001 for x in D]
            ax[0].plot(Dd, [w * 1e3 for w in rec["W"]], mk, label=lab)
            grid = [min(D) * 0.8 + i * (max(D) * 1.1 - min(D) * 0.8) / 60 for i in range(61)]
            ax[0].plot([g / 0.001 for g in grid], [w * 1e3 for w in beverloo_curve(rec["C"], rec["k"], rec["rho_b"], grid)],
                       "-", lw=0.8, label=f"fit C = {rec['C']:.3f}, k = {rec['k']:.2f}")
            ax[1].plot(Dd, [(w / (rec["rho_b"] * math.sqrt(9.81))) ** 0.4 / 0.001 for w in rec["W"]], mk, label=lab)
            g2 = [rec["k"]] + [x for x in [g / 0.001 for g in grid]]
            ax[1].plot(g2, [rec["C"] ** 0.4 * max(x - rec["k"], 0) for x in g2], "-", lw=0.8)
        ref = refs["beverloo_C"]["reference"]
        dmax = max(max(r["D"]) for r in (bv_ci, bv_long) if r) / 0.001 * 1.1
        gx = [1.5 + i * (dmax - 1.5) / 60 for i in range(61)]
        ax[1].plot(gx, [ref ** 0.4 * (x - 1.5) for x in gx], "k--", lw=0.8, label="C = 0.58, k = 1.5")
        ax[0].set_xlabel("orifice diameter D / d")
        ax[0].set_ylabel("mass flow rate W (g/s)")
        ax[0].legend(fontsize=7)
        ax[1].set_xlabel("D / d")
        ax[1].set_ylabel("(W / ρ_b √g)^(2/5) / d")
        ax[1].set_xlim(0, None)
        ax[1].set_ylim(0, None)
        ax[1].legend(fontsize=7)
        plt.tight_layout()
        plt.savefig(os.path.join(FIG, "beverloo.png"), dpi=120)
        plt.close()
        figs.append(("beverloo.png", "Silo discharge: mass flow rate against orifice diameter and the Beverloo fit "
                                     "(right: the linearised form, whose intercept on the axis is k)."))
    if jam_ci or jam_long:
        fig, ax = plt.subplots(1, 2, figsize=(8, 3.2))
        pts = []
        if jam_ci:
            pts.append(("CI N=2,000", [jam_ci["phi"]], [jam_ci["z_rigid"]]))
        if jam_long:
            pts.append(("long N=10,000", jam_long["phi_all"], jam_long["z_rigid_all"]))
        for i, (lab, ph, zz) in enumerate(pts):
            ax[0].plot([i] * len(ph), ph, "o")
            ax[1].plot([i] * len(zz), zz, "o")
        for a, key in ((ax[0], "jamming_phi"), (ax[1], "jamming_z")):
            b = refs[key]["band"]
            a.axhspan(b[0], b[1], color="tab:green", alpha=0.15)
            a.axhline(refs[key]["reference"], color="gray", ls="--", lw=0.8)
            a.set_xticks(range(len(pts)))
            a.set_xticklabels([p[0] for p in pts])
            a.set_xlim(-0.5, len(pts) - 0.5)
        ax[0].set_ylabel("packing fraction φ")
        ax[1].set_ylabel("Z without rattlers")
        plt.tight_layout()
        plt.savefig(os.path.join(FIG, "jamming.png"), dpi=120)
        plt.close()
        figs.append(("jamming.png", "Frictionless spheres jammed by growing radii: φ and Z per run against the "
                                    "accepted bands (shaded) and the references (dashed)."))
    if ell_sweep:
        plt.figure(figsize=(5.2, 3.6))
        plt.errorbar(ell_sweep["aspect_ratio"], ell_sweep["phi"], yerr=ell_sweep["phi_se"], fmt="o-", capsize=3,
                     label=f"long: 1,000 spheroids, mean of {ell_sweep['seeds']} seed(s)")
        if ell_ci:
            plt.plot([1, 1.5], [ell_ci["phi_ar1"], ell_ci["phi_ar1_5"]], "s", label="CI: 500 spheroids, 2 seeds")
        plt.axvline(1.8, color="gray", ls="--", lw=0.8)
        plt.text(1.82, min(ell_sweep["phi"]), "Zhou et al. maximum ≈ 1.8", color="gray", fontsize=8)
        plt.xlabel("aspect ratio (prolate)")
        plt.ylabel("bulk packing fraction φ")
        plt.legend(fontsize=7)
        plt.tight_layout()
        plt.savefig(os.path.join(FIG, "ellipsoids.png"), dpi=120)
        plt.close()
        figs.append(("ellipsoids.png", "Poured frictional spheroids: bulk packing fraction against aspect ratio."))

    if dim_sweep:
        plt.figure(figsize=(5.2, 3.6))
        plt.errorbar(dim_sweep["aspect_ratio"], dim_sweep["phi"], yerr=dim_sweep["phi_se"], fmt="o-", capsize=3,
                     label="long: 1,200 frictionless dimers, 2 seeds")
        if dim_ci:
            plt.plot([1.5], [dim_ci["phi_dimers"]], "s", label="CI: aspect ratio 1.5, 1 seed")
        plt.axvspan(1.4, 1.5, color="gray", alpha=0.2, label="densest jammed dimers (Baule 2013)")
        plt.xlabel("bond aspect ratio (l + 2a) / 2a")
        plt.ylabel("bulk packing fraction φ")
        plt.legend(fontsize=7)
        plt.tight_layout()
        plt.savefig(os.path.join(FIG, "dimers.png"), dpi=120)
        plt.close()
        figs.append(("dimers.png", "Poured frictionless dimers of the volume of a sphere: bulk packing fraction "
                                   "against bond aspect ratio (1 = spheres)."))

    if res:
        plt.figure(figsize=(5.2, 3.6))
        plt.errorbar(res["n3"], res["phi"], yerr=res["phi_se"], fmt="o-", capsize=3,
                     label=f"long: 250 cubes, mean ± s.e. of {len(res['phi_all']) // len(res['grid'])} seeds")
        for g, n, p in zip(res["grid"], res["n3"], res["phi"]):
            plt.annotate(f"grid {g:g}", (n, p), fontsize=7, textcoords="offset points", xytext=(4, 4))
        if res_ci:
            plt.plot([res["n3"][0], res["n3"][1]], [res_ci["phi_grid4"], res_ci["phi_grid6"]], "s",
                     label="CI: grid 4 and 6, seed 1")
        plt.xscale("log")
        plt.xlabel("balls per cube n₃")
        plt.ylabel("bulk packing fraction φ")
        plt.legend(fontsize=7)
        plt.tight_layout()
        plt.savefig(os.path.join(FIG, "clump_resolution.png"), dpi=120)
        plt.close()
        figs.append(("clump_resolution.png", "Poured frictional cube clumps in a periodic box: bulk packing "
                                             "fraction against the number of balls per cube."))

    # ------------------------------------------------------------ text
    today = meta.get("date", datetime.date.today().isoformat())
    L = []
    L.append("# Packing fractions and flows: the regression suite\n")
    L.append("Generated by `bash tests/regression/make_packing_doc.sh` (do not edit by hand) on "
             f"{today}, {meta.get('machine', 'unknown machine')}, at commit {meta.get('commit', '?')}. The tests, their sizes and the "
             "protocols are in tests/regression/ (packing_support.hpp); every reference value, the band a "
             "test accepts, why, and its source are in tests/regression/packing_references.yaml, which "
             "the tests read. CI sizes run in the default suite (label `regression`, "
             "`ctest --test-dir build -LE long`); full sizes run with `ctest --test-dir build -L long` "
             "or this script.\n")
    commits = {}
    for name in sorted(os.listdir(results)):
        if name.endswith(".commit"):
            commits.setdefault(open(os.path.join(results, name)).read().strip(), []).append(name[:-7])
    if commits:
        L.append("Measured at: " + "; ".join(f"{c}: {', '.join(v)}" for c, v in commits.items()) + ".\n")
    L.append("## Results\n")
    L.append("| quantity | CI | long | reference | accepted | inside (CI / long) | source | key |")
    L.append("|---|---|---|---|---|---|---|---|")
    L.extend(rows)
    L.append("")
    for name, cap in figs:
        L.append(f"![{cap}](packing/{name})\n")
        L.append(f"*{cap}*\n")

    L.append("## Friction sweep (poured spheres)\n")
    L.append("cases/pour_spheres: spheres of d = 1 mm, ρ = 2500 kg/m³, E = 10 MPa, ν = 0.3, e = 0.5 "
             "(walls of the same material), random loose fill at a solid fraction of about 0.26, poured "
             "under gravity and settled (rms speed of the bulk grains below 5 % of √(2 g d)); friction μ of grains and walls "
             "swept; no rolling friction. Bulk region 2 d from the side walls, the floor and the free "
             "surface, exact sphere–box volumes. CI: 3,000 spheres in a 10 d × 10 d box, 0.3 s (0.4 s without "
             "friction, where only the normal damping stops the grains), one seed; long: 10,000 spheres in "
             "20 d × 20 d, 0.35 s (0.45 s), two seeds.\n")
    if fr_ci:
        L.append("| μ | " + " | ".join(f"{m:g}" for m in fr_ci["mu"]) + " |")
        L.append("|---|" + "---|" * len(fr_ci["mu"]))
        L.append("| φ CI (seed 1) | " + " | ".join(f"{p:.4f}" for p in fr_ci["phi"]) + " |")
        if fr_long:
            L.append("| φ long (mean ± s.d.) | " + " | ".join(
                f"{p:.4f} ± {s:.4f}" for p, s in zip(fr_long["phi"], fr_long["phi_sd"])) + " |")
        L.append("")
    fs = load(results, "friction_seeds_ci")
    if fs:
        L.append("The CI configuration over seeds " + ", ".join(str(int(x)) for x in fs["seeds"]) +
                 " (PackingLong.FrictionSweepSeedSpread): " + "; ".join(
                     f"μ = {m:g}: {p:.4f} ± {sd:.4f}" for m, p, sd in zip(fs["mu"], fs["phi"], fs["phi_sd"])) +
                 f" (mean ± s.d.), pooled standard deviation of one run {fs['pooled_sd']:.4f} against "
                 f"{fs['sigma_used']:.4f} assumed by the CI test; smallest mean step "
                 f"{fs['smallest_step']:.4f}.\n")
    how_many = (f"{fs['smallest_step'] / (math.sqrt(2) * fs['sigma_used']):.1f}" if fs else "several")
    L.append("The CI test requires every step to fall (the smallest mean step is " + how_many +
             " standard deviations of a difference of two runs) and φ(0) − φ(1) above 5 standard deviations of a difference. The trend is that of Silbert (2010): frictionless grains "
             "compact to about the jamming density, friction stabilises looser structures and the curve "
             "flattens above μ ≈ 0.5 towards random loose packing (0.55 at μ → ∞ and vanishing pressure, "
             "Jerkins et al. 2008; a pour under gravity stays above it).\n")

    L.append("## Silo discharge against Beverloo\n")
    L.append("cases/silo_discharge: a flat-bottomed cylinder (a finite plane wall with a circular hole, "
             "docs/physics.md) filled with spheres of d = 1 mm, E = 2.5 MPa, e = 0.5, μ = 0.5 (grains and "
             "walls) while the hole is closed; from copies of the settled fill the orifice is opened to "
             "each diameter D and the mass above the bottom is sampled every 2 ms. W is minus the "
             "least-squares slope of that mass against time after a transient; the steadiness check "
             "compares the two halves of the window. ρ_b = 2500 φ_b with φ_b the bulk packing fraction of "
             "the fill (a square column 2 d inside the cylinder). C and k from the least-squares line "
             "W^(2/5) = (C ρ_b √g)^(2/5) (D − k d) (standard errors from the residuals).\n")
    for rec, name in ((bv_ci, "CI (silo 20 d, 6,000 grains, 0.24 s per orifice)"),
                      (bv_long, "long (silo 26 d, 24,300 grains, bed > 1.2 silo diameters, 0.4 s per orifice)")):
        if not rec:
            continue
        L.append(f"**{name}**: φ_b = {rec['rho_b'] / 2500:.4f}; " + ", ".join(
            f"D = {d / 0.001:g} d: W = {w * 1e3:.3f} g/s" for d, w in zip(rec["D"], rec["W"])) +
                 f"; two-parameter fit C = {rec['C']:.3f} ± {rec['se_C']:.3f}, k = {rec['k']:.2f} ± "
                 f"{rec['se_k']:.2f} (R² of W^(2/5) against D {rec['r2']:.4f}); exponent of D − 1.5 d "
                 f"{rec['exponent']:.2f} ± {rec['se_exponent']:.2f}" +
                 (f"; C with k = 1.5: {rec['C_fixed_k']:.3f}" if "C_fixed_k" in rec else "") + ".\n")
    L.append("The grains pass the orifice nearly at random: over a window holding N grains the rate is known "
             "to about 1/√N, which is why the CI, with a few hundred grains "
             "at the smallest orifice, checks C with the published k and the 5/2 exponent, and leaves the "
             "two-parameter fit to the long run.\n")
    L.append("## Jamming of frictionless spheres\n")
    L.append("cases/jam_frictionless: frictionless spheres (E = 10 MPa, e = 0.1) placed at random in a "
             "periodic cube at a solid fraction of 0.23 and compressed by growing radii "
             "(`radius_growth`, docs/physics.md) in four phases: fast growth to a dense agitated fluid, "
             "slow growth until it jams at an overlap per particle of 2e-3, decompression to 5e-4, "
             "relaxation at fixed radii (the case's README). φ = Σ (4/3) π r³ / L³ of the periodic box; "
             "contacts by global id (each periodic pair once); rattlers (fewer than 4 contacts) removed "
             "iteratively with their contacts (O'Hern et al. 2003).\n")
    if jam_ci:
        L.append(f"CI (N = 2,000, seed 1): φ = {jam_ci['phi']:.4f}, Z = {jam_ci['z']:.3f}, Z without rattlers "
                 f"{jam_ci['z_rigid']:.3f}, rattlers {100 * jam_ci['rattlers']:.1f} %, overlap per particle "
                 f"{jam_ci['overlap_per_particle']:.2e}.\n")
    if jam_long:
        L.append("Long (N = 10,000, seeds 1–3): φ = " + ", ".join(f"{p:.4f}" for p in jam_long["phi_all"]) +
                 "; Z without rattlers " + ", ".join(f"{z:.3f}" for z in jam_long["z_rigid_all"]) +
                 "; rattlers " + ", ".join(f"{100 * r:.1f} %" for r in jam_long["rattlers_all"]) + ".\n")

    L.append("How to read these: the protocol is dynamic (the DEM's own contact damping relaxes the packing, "
             "no energy minimiser), so the packing is measured while it still creeps slowly — the kinetic energy "
             "is below 1 % of the elastic energy and the total energy falls monotonically, but contacts whose "
             "overlap" + (f" (mean {jam_ci['mean_relative_overlap']:.1e} of r_i + r_j in CI)" if jam_ci else "") +
             " is below the residual vibration open and close, which is "
             "why Z without rattlers comes out a little below the isostatic 6 rather than a little above it, as "
             "it would in a static packing at this small pressure. The compression rate of the slow phase "
             "(d ln r/dt ≤ 0.5/s) is what sets φ within the protocol-dependent range of random close packing (fast quenches give less, slow compressions "
             "more).\n")
    L.append("## Ellipsoids and dimers\n")
    if ell_ci:
        L.append(f"CI (tests/regression/test_ellipsoid_packing.cpp: 500 prolate spheroids, μ = 0.5, seeds 1 "
                 f"and 2): φ(1) = {ell_ci['phi_ar1']:.4f}, φ(1.5) = {ell_ci['phi_ar1_5']:.4f}, rise "
                 f"{ell_ci['rise']:.4f}.\n")
    if ell_sweep:
        L.append("Long (tests/regression/ellipsoid_packing_sweep.sh: 1,000 prolate spheroids poured into a "
                 "10 d × 10 d column, μ = 0.5, e = 0.5; bulk φ by `grains analyze`, Monte Carlo union volume):\n")
        L.append("| aspect ratio | " + " | ".join(f"{a:g}" for a in ell_sweep["aspect_ratio"]) + " |")
        L.append("|---|" + "---|" * len(ell_sweep["aspect_ratio"]))
        L.append("| φ (mean of seeds " + ", ".join(str(s) for s in ell_sweep["seed_list"]) + ") | " +
                 " | ".join(f"{p:.4f} ± {e:.4f}" for p, e in zip(ell_sweep["phi"], ell_sweep["phi_se"])) + " |")
        L.append("| nematic S | " + " | ".join(f"{s:.3f}" for s in ell_sweep["nematic_S"]) + " |")
        L.append("")
        L.append(f"Maximum at aspect ratio {ell_sweep['peak_aspect_ratio']:g} (Zhou et al. 2011: ≈ 1.8 for "
                 "prolate spheroids); non-monotonic: " + ("yes" if ell_sweep["non_monotonic"] else "NO") + ".\n")
    if dim_ci:
        L.append(f"Dimers (tests/regression/clump/test_clump_packing.cpp, CI: 1,200 frictionless grains, e = 0.1, "
                 f"10 d × 10 d): spheres φ = {dim_ci['phi_spheres']:.4f}, dimers of bond aspect ratio 1.5 "
                 f"φ = {dim_ci['phi_dimers']:.4f} (rise {dim_ci['rise']:.4f}; Baule et al. 2013: jammed dimers "
                 "peak near 0.70 at aspect ratio 1.4–1.5).\n")
    if dim_sweep:
        L.append("Long (tests/regression/clump/test_clump_packing_long.cpp: the same pour, bond aspect ratios "
                 "1–2 at the volume of a sphere, placement seeds 3 and 5):\n")
        L.append("| bond aspect ratio | " + " | ".join(f"{a:g}" for a in dim_sweep["aspect_ratio"]) + " |")
        L.append("|---|" + "---|" * len(dim_sweep["aspect_ratio"]))
        L.append("| φ (mean ± s.e.) | " + " | ".join(
            f"{p:.4f} ± {e:.4f}" for p, e in zip(dim_sweep["phi"], dim_sweep["phi_se"])) + " |")
        L.append("")
        L.append(f"Densest at aspect ratio {dim_sweep['peak_aspect_ratio']:g} (Baule et al. 2013: 1.4–1.5 for "
                 "jammed frictionless dimers).\n")
    if res or res_ci:
        L.append("## Clump resolution: φ of poured cubes against n₃\n")
        L.append("tests/regression/clump (clump_pour.hpp, `pour_periodic`): cases/pour_clumps/cube.off decomposed at "
                 "grid N (μ = 0.25), 250 cubes of bounding radius 0.8 mm poured from a random fill up to 64 mm "
                 "onto a floor in a 6 mm × 6 mm box periodic in x and y (no side walls), E = 1 MPa, e = 0.5, "
                 "friction 0.5, 0.18 s; φ of the union of balls (grid of sample points, periodic images) from "
                 "2 mm above the floor to 2 mm below the free surface.\n")
    if res:
        L.append("| grid N | " + " | ".join(f"{g:g}" for g in res["grid"]) + " |")
        L.append("|---|" + "---|" * len(res["grid"]))
        L.append("| n₃ | " + " | ".join(f"{n:g}" for n in res["n3"]) + " |")
        L.append("| φ (mean ± s.e.) | " + " | ".join(
            f"{p:.4f} ± {e:.4f}" for p, e in zip(res["phi"], res["phi_se"])) + " |")
        L.append("| s per pour | " + " | ".join(f"{w:.0f}" for w in res["wall_s_per_pour"]) + " |")
        L.append("")
        L.append("Changes between successive grids: " + ", ".join(
            f"{a:g} → {b:g}: {d:+.4f} ± {e:.4f}" for a, b, d, e in
            zip(res["grid"], res["grid"][1:], res["change"], res["change_se"])) + " (± s.e.).\n")
    if res_ci:
        L.append(f"CI (seed 1): φ(grid 4) = {res_ci['phi_grid4']:.4f}, φ(grid 6) = {res_ci['phi_grid6']:.4f}, "
                 f"step {res_ci['step']:.4f}.\n")
    with open(DOC, "w") as f:
        f.write("\n".join(L).rstrip() + "\n")
    print("wrote", DOC, "and", len(figs), "plots in", FIG)


if __name__ == "__main__":
    main()
