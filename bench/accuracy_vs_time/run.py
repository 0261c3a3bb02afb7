#!/usr/bin/python3
"""Accuracy against time: runs the sweeps and writes docs/accuracy-vs-time.md.

    /usr/bin/python3 bench/accuracy_vs_time/run.py [--build DIR] [--out DIR] [--quick] [--only 1,2,...]

Sections (issue 8): 1 PW85 solver tolerance, 2 time integration (Verlet and
ARKODE; a two-body impact and a small pour), 3 clump resolution, 4 NFFT
tolerance and truncated modes, 5 neighbour skin. Every figure comes from
runs made here: the helper programs of this folder (accuracy_*) and the
`grains` command line. --quick runs every sweep at a couple of points into
--out (the CTest smoke test); the full report takes about 15 minutes on the
2-core machine of bench/RESULTS.md. Needs Debian's python3-matplotlib.
"""
import argparse
import datetime
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


# ---------------------------------------------------------------- helpers


def sh(cmd, check=True, env=None):
    """Runs a command, returns (exit code, stdout, stderr)."""
    e = dict(os.environ)
    e.setdefault("OMP_NUM_THREADS", "1")
    if env:
        e.update(env)
    p = subprocess.run(cmd, capture_output=True, text=True, env=e)
    if check and p.returncode != 0:
        raise RuntimeError("failed: %s\n%s%s" % (" ".join(cmd), p.stdout[-2000:], p.stderr[-2000:]))
    return p.returncode, p.stdout, p.stderr


def machine():
    model, cpus, tpc = "?", "?", "?"
    try:
        out = sh(["lscpu"])[1]
        for line in out.splitlines():
            k, _, v = line.partition(":")
            v = v.strip()
            if k.strip() == "Model name":
                model = v
            elif k.strip() == "CPU(s)":
                cpus = v
            elif k.strip() == "Thread(s) per core":
                tpc = v
    except Exception:
        pass
    return {"model": model, "cpus": cpus, "threads_per_core": tpc}


def fmt(x, digits=3):
    if x is None:
        return "–"
    if isinstance(x, str):
        return x
    if isinstance(x, int):
        return str(x)
    if x == 0:
        return "0"
    if not math.isfinite(x):
        return str(x)
    a = abs(x)
    if a >= 1e4 or a < 1e-3:
        return "%.*e" % (digits - 1, x)
    return "%.*g" % (digits, x)


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for r in rows:
        out.append("| " + " | ".join(fmt(c) if not isinstance(c, str) else c for c in r) + " |")
    return "\n".join(out)


def gbench(exe, filt, reps, min_time, quick):
    """Runs a Google Benchmark program; returns {name: {'time': median real time, counters...}}."""
    cmd = [exe, "--benchmark_format=json", "--benchmark_filter=" + filt,
           "--benchmark_min_time=%g" % min_time]
    if reps > 1:
        cmd += ["--benchmark_repetitions=%d" % reps, "--benchmark_report_aggregates_only=true"]
    out = sh(cmd)[1]
    data = json.loads(out)
    res = {}
    for b in data["benchmarks"]:
        name = b.get("run_name", b["name"]).replace("/real_time", "")
        if reps > 1 and b.get("aggregate_name") != "median":
            continue
        unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
        d = {k: v for k, v in b.items() if isinstance(v, (int, float))}
        d["seconds"] = b["real_time"] * unit
        res[name] = d
    return res


class Report:
    def __init__(self, out_dir, fig_dir_name, quick):
        self.out_dir = out_dir
        self.fig_dir = os.path.join(out_dir, fig_dir_name)
        self.fig_rel = fig_dir_name
        os.makedirs(self.fig_dir, exist_ok=True)
        self.parts = []
        self.quick = quick

    def add(self, text):
        self.parts.append(text.strip("\n") + "\n")

    def figure(self, fig, name, caption):
        path = os.path.join(self.fig_dir, name)
        fig.savefig(path, dpi=110, bbox_inches="tight")
        plt.close(fig)
        self.add("![%s](%s/%s)\n" % (caption, self.fig_rel, name))


# ---------------------------------------------------------------- 1: PW85


def section_pw85(rep, build, quick, env_line):
    exe = os.path.join(build, "bench", "accuracy_vs_time", "accuracy_pw85")
    ars = [2, 10] if quick else [1, 2, 10, 100, 1000]
    ks = [2, 4] if quick else [1, 2, 3, 4, 5, 7]
    reps = 1 if quick else 3
    filt = "BM_(Cold|Warm|EarlyExit)/(%s)/(%s)$" % ("|".join(map(str, ars)), "|".join(map(str, ks)))
    r = gbench(exe, filt, reps, 0.01 if quick else 0.05, quick)
    rep.add("""
## 1. Contact function (PW85): solver tolerance

`accuracy_pw85` (this folder): 1024 random pairs per aspect-ratio class
(prolate, oblate and triaxial bodies, random orientations and sizes; the
pairs of bench/pw85), Newton tolerance τ on the step in u = log(λ/(1−λ))
(docs/pw85.md; the DEM uses τ = 1e-4, the default is 1e-7). **Cold**:
touching pairs (μ² ∈ [0.5, 1]) from λ = ½; **warm**: the same kind of
pairs one DEM step later (bodies turned by 1e-3 rad and moved by 1e-3 of
their small axis), started from the previous step's λ; **early exit**:
separated pairs inside a Verlet skin (μ² ∈ [1.2, 4]) with
`stop_if_separated`. Error: relative error of μ² against the __float128
reference of the unit tests over 128 pairs (max and mean); early exits
have no μ² to compare, so the check is that no pair is classified wrongly.
Time: wall-clock ns per call (%s).
""" % env_line)
    modes = [("Cold", "cold start"), ("Warm", "warm start")]
    for mode, title in modes:
        rows = []
        for k in ks:
            row = ["1e-%d" % k]
            for ar in ars:
                d = r.get("BM_%s/%d/%d" % (mode, ar, k))
                row.append("%s / %s / %.1f" % (fmt(d["max_rel_err"], 2), fmt(d["seconds"] * 1e9, 3), d["evals"])
                           if d else "–")
            rows.append(row)
        rep.add("**%s**: max relative error of μ² / ns per call / f evaluations per call\n" % title)
        rep.add(table(["τ"] + ["aspect %d" % a for a in ars], rows) + "\n")
    rows = []
    for k in ks:
        row = ["1e-%d" % k]
        for ar in ars:
            d = r.get("BM_EarlyExit/%d/%d" % (ar, k))
            row.append("%s / %.2f / %d" % (fmt(d["seconds"] * 1e9, 3), d["evals"], int(d["wrong_decisions"]))
                       if d else "–")
        rows.append(row)
    rep.add("**early exit** (separated pairs): ns per call / f evaluations per call / wrong decisions of 1024\n")
    rep.add(table(["τ"] + ["aspect %d" % a for a in ars], rows) + "\n")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    for ax, (mode, title) in zip(axes, modes):
        for ar in ars:
            xs, ys, ls = [], [], []
            for k in ks:
                d = r.get("BM_%s/%d/%d" % (mode, ar, k))
                if d:
                    xs.append(d["seconds"] * 1e9)
                    ys.append(max(d["max_rel_err"], 1e-17))
                    ls.append(k)
            ax.loglog(xs, ys, "o-", label="aspect %d" % ar)
            for x, y, k in zip(xs, ys, ls):
                ax.annotate("%d" % k, (x, y), fontsize=7, textcoords="offset points", xytext=(3, 3))
        ax.axhline(2.2e-16, color="grey", lw=0.5, ls=":")
        ax.set_xlabel("ns per call")
        ax.set_ylabel("max relative error of μ²")
        ax.set_title("PW85 %s (labels: τ = 1e-k)" % title)
        ax.legend(fontsize=7)
    rep.figure(fig, "pw85.png", "PW85 error against time")
    return r


# ---------------------------------------------------------------- 2: integration


def impact(build, args):
    exe = os.path.join(build, "bench", "accuracy_vs_time", "accuracy_impact")
    return json.loads(sh([exe] + args)[1])


def pour_run(build, case, out, sets, quiet=True):
    """grains run; returns (summary dict or None, error text)."""
    cmd = [os.path.join(build, "grains"), "run", case, "-o", out, "-q"]
    for s in sets:
        cmd += ["--set", s]
    code, so, se = sh(cmd, check=False)
    if code != 0:
        msg = (se.strip().splitlines() or ["exit %d" % code])[-1]
        return None, msg
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f), ""


def analyze_phi(build, out, region=None):
    """(phi, its sampling error, None) or (None, None, why grains analyze refused)."""
    cmd = [os.path.join(build, "grains"), "analyze", out, "-o", os.path.join(out, "analysis"), "--no-plots"]
    if region:
        cmd += ["--region", ",".join("%g" % v for v in region)]
    code, so, se = sh(cmd, check=False)
    if code != 0:
        return None, None, (se.strip().splitlines() or ["exit %d" % code])[-1]
    with open(os.path.join(out, "analysis", "analysis.json")) as f:
        a = json.load(f)
    return a["packing_fraction"]["value"], a["packing_fraction"].get("error", 0.0), None


def section_integration(rep, build, quick, env_line, work):
    reps = 1 if quick else 5
    rep.add("""
## 2. Time integration: Verlet and ARKODE

Velocity Verlet with the time step dt as a fraction of the Rayleigh time
T_R (and of the Hertz contact time t_c), against SUNDIALS ARKODE (explicit
adaptive Runge–Kutta, order 4, `integrator: arkode`, docs/integrators.md)
at several tolerances (rtol = atol; dt = T_R is then only ARKODE's largest
step). %s.
""" % env_line)
    # --- the two-body impact
    fr = [1.0, 0.5, 0.3] if quick else [1.0, 0.8, 0.5, 0.3, 0.2, 0.1, 0.05, 0.02, 0.01]
    tols = [1e-3, 1e-6] if quick else [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]
    rows, pts = [], {"verlet": [], "arkode": []}
    probe = impact(build, ["--integrator", "verlet", "--dt-rayleigh", "0.1", "--reps", "1"])
    refused = impact(build, ["--integrator", "verlet", "--dt-seconds", "%.6g" % (1.5 * probe["rayleigh_time"]),
                             "--reps", "1"])
    for kind, values in (("verlet", fr), ("arkode", tols)):
        for v in values:
            common = ["--reps", str(reps), "--v", "0.5"]
            if kind == "verlet":
                a = ["--integrator", "verlet", "--dt-rayleigh", str(v)] + common
            else:
                a = ["--integrator", "arkode", "--tol", "%g" % v, "--dt-rayleigh", "1"] + common
            el = impact(build, a + ["--e", "1"])
            da = impact(build, a + ["--e", "0.5"])
            if not el.get("ok") or not da.get("ok"):
                rows.append([kind, fmt(v), "failed: " + (el.get("error") or da.get("error"))] + ["–"] * 7)
                continue
            tr, tc = el["rayleigh_time"], el["tc_hertz"]
            st = el.get("stats") or {}
            steps = st.get("accepted_steps", el["clock_steps"])
            rhs = st.get("rhs_evaluations", 0) + st.get("projection_evaluations", 0) + st.get("end_evaluations", 0)
            rhs = rhs or el["clock_steps"]
            e_err = abs(da["restitution"] - 0.5)
            en = abs(el["energy_error"])
            ov = abs(el["max_overlap"] / el["dmax_hertz"] - 1)
            tce = abs(el["contact_time"] / tc - 1)
            wall = el["wall_median_s"]
            if kind == "verlet":
                dts = "%.3g / %.3g" % (v, v * tr / tc)
            else:  # the range of accepted steps
                dts = "%s–%s / %s–%s" % (fmt(st["min_step_s"] / tr, 2), fmt(st["max_step_s"] / tr, 2),
                                        fmt(st["min_step_s"] / tc, 2), fmt(st["max_step_s"] / tc, 2))
            rows.append([kind, ("%.3g T_R" % v) if kind == "verlet" else "tol %g" % v, dts,
                         steps, rhs, wall * 1e3, e_err, en, ov, tce])
            pts[kind].append((wall, e_err, en, ov, tce, v))
    rep.add("""
### Two-body impact

Two 1 mm spheres (E = 10 MPa, ν = 0.3, ρ = 2500 kg/m³) meet head-on at
±0.5 m/s (`accuracy_impact`, the set-up of tests/physics/arkode):
t_c = 2.4 T_R. Elastic run (e = 1): energy error |e² − 1|, maximum
overlap and contact time against Hertz (overlap sampled at every step,
cubic Hermite in between; contact time from the free flights before and
after, which both integrators integrate exactly). Damped run (e = 0.5):
restitution error against the calibrated target (which is itself exact
to ~1e-7, sim/laws/restitution.cpp). Wall time: the time loop of the
elastic run, median of %d. For ARKODE, dt is the range of its accepted
steps (tiny ones where a contact begins or ends) and "force evaluations"
counts every force phase (trial stages, rejected steps, the clock-step
ends). A time step
above T_R is refused at set-up: `%s`.
""" % (reps, refused.get("error", "?")))
    rep.add(table(["integrator", "setting", "dt/T_R / dt/t_c", "steps", "force evaluations", "wall ms",
                   "restitution error (e=0.5)", "energy error (e=1)", "max overlap error", "contact time error"],
                  rows) + "\n")
    fig, axes = plt.subplots(1, 4, figsize=(16, 3.8))
    names = ["restitution error (e = 0.5)", "energy error |e²−1| (e = 1)", "max overlap error", "contact time error"]
    for i, ax in enumerate(axes):
        for kind, mk in (("verlet", "o-"), ("arkode", "s-")):
            p = pts[kind]
            if not p:
                continue
            xs = [q[0] * 1e3 for q in p]
            ys = [max(q[1 + i], 1e-12) for q in p]
            ax.loglog(xs, ys, mk, label="verlet (labels: dt/T_R)" if kind == "verlet" else "arkode (labels: tol)")
            for q, x, y in zip(p, xs, ys):
                ax.annotate(("%g" % q[5]), (x, y), fontsize=6, textcoords="offset points", xytext=(2, 2))
        ax.set_xlabel("wall ms (median)")
        ax.set_title(names[i], fontsize=9)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("relative error")
    rep.figure(fig, "impact.png", "impact errors against wall time")

    # --- the small pour
    case = os.path.join(HERE, "pour_small.yaml")
    seeds = [1] if quick else [1, 2, 3]
    vf = [0.3, 1.0] if quick else [0.1, 0.2, 0.3, 0.5, 0.8, 1.0]
    at = [1e-2] if quick else [1e-2, 1e-3, 1e-4]
    end = ["time.end=0.01"] if quick else []
    rows, pts = [], []
    for kind, values in (("verlet", vf), ("arkode", at)):
        for v in values:
            phis, walls, steps, evals, fails, lost, notes = [], [], [], [], [], [], []
            # ARKODE at 1e-4 costs minutes per run: one seed.
            run_seeds = seeds[:1] if kind == "arkode" and v < 1e-3 else seeds
            for seed in run_seeds:
                out = os.path.join(work, "pour_%s_%g_%d" % (kind, v, seed))
                sets = ["particles.0.placement.seed=%d" % seed] + end
                if kind == "verlet":
                    sets.append("time.dt_rayleigh=%g" % v)
                else:
                    sets += ["time.integrator=arkode", "time.rtol=%g" % v, "time.atol=%g" % v, "time.dt_rayleigh=1"]
                s, err = pour_run(build, case, out, sets)
                if s is None:
                    fails.append(err)
                    continue
                walls.append(s["wall_time_s"])
                det = next(iter(s.get("stage_details", {}).values()), {})
                steps.append(det.get("accepted_steps", s["steps"]))
                evals.append(det.get("rhs_evaluations", 0) + det.get("projection_evaluations", 0)
                             + det.get("end_evaluations", 0) or s["steps"])
                lost.append(s["lost_particles"])
                if not quick:
                    phi, _, why = analyze_phi(build, out)
                    if phi is None:
                        notes.append("seed %d: %s" % (seed, why))
                    else:
                        phis.append(phi)
            label = ("%g T_R" % v) if kind == "verlet" else "tol %g" % v
            if fails:
                rows.append([kind, label, "%d of %d failed: %s" % (len(fails), len(run_seeds), fails[0])] + ["–"] * 6)
            if walls:
                phi = statistics.mean(phis) if phis else None
                spread = statistics.pstdev(phis) if len(phis) > 1 else None
                rows.append([kind, label, len(walls), statistics.median(steps), statistics.median(evals),
                             statistics.median(walls), sum(lost), phi, spread])
                for n in notes:
                    rows.append(["", "", "no φ: " + n, "", "", "", "", "", ""])
                if phi is not None:
                    pts.append((kind, v, statistics.median(walls), phi, spread or 0))
    rep.add("""
### Small pour

`pour_small.yaml` (this folder): 500 spheres, d = 1 mm, e = 0.5, μ = 0.5,
poured into an 8 d × 8 d box, %s of simulated time; seeds %s of the random
fill. Packing fraction: `grains analyze` (exact sphere volumes in the
automatic bulk region, 2 d from walls, floor and free surface), mean and
population standard deviation over the seeds (ARKODE at 1e-4: one seed,
it takes minutes). Wall: `summary.json`, median over the seeds. A run that fails (blow-up diagnosed by the run, or a
set-up refusal) is listed with its message; "particles lost" counts
particles that left the box (through a wall: an unresolved contact),
summed over the seeds, and a bed `grains analyze` cannot find a bulk
region in is listed with its reason.
""" % ("0.01 s (quick)" if quick else "0.12 s", ", ".join(map(str, seeds))))
    rep.add(table(["integrator", "setting", "seeds", "steps", "force evaluations", "wall s", "particles lost",
                   "φ (mean)", "φ spread (std)"], rows) + "\n")
    if pts:
        fig, ax = plt.subplots(figsize=(6, 4))
        for kind, mk in (("verlet", "o"), ("arkode", "s")):
            p = [q for q in pts if q[0] == kind]
            ax.errorbar([q[2] for q in p], [q[3] for q in p], yerr=[q[4] for q in p], fmt=mk + "-", label=kind,
                        capsize=3)
            for q in p:
                ax.annotate("%g" % q[1], (q[2], q[3]), fontsize=7, textcoords="offset points", xytext=(3, 3))
        ax.set_xscale("log")
        ax.set_xlabel("wall s (median over seeds)")
        ax.set_ylabel("bulk packing fraction (± std over seeds)")
        ax.set_title("small pour: φ against wall time")
        ax.legend()
        rep.figure(fig, "pour.png", "poured packing fraction against wall time")


# ---------------------------------------------------------------- 3: clumps


def clump_table(build, mesh, grid, work):
    out = os.path.join(work, "clump_%d.yaml" % grid)
    txt = sh([os.path.join(build, "grains"), "clump", mesh, "--grid", str(grid), "-o", out])[1]
    balls = int(re.search(r"n3 = (\d+)", txt).group(1))
    haus = float(re.search(r"^hausdorff\s+([0-9.eE+-]+)", txt, re.M).group(1))
    vol = float(re.search(r"error ([+-]?[0-9.eE+-]+) %", txt).group(1))
    return balls, haus, vol


def section_clumps(rep, build, quick, env_line, work):  # noqa: C901
    mesh = os.path.join(ROOT, "cases", "pour_clumps", "cube.off")
    grids = [4, 6] if quick else [4, 6, 8, 16]
    case = os.path.join(HERE, "pour_clumps_small.yaml")
    end = ["time.end=0.005"] if quick else []
    rows, pts = [], []
    for g in grids:
        balls, haus, vol = clump_table(build, mesh, g, work)
        out = os.path.join(work, "clumps_%d" % g)
        s, err = pour_run(build, case, out, ["particles.0.shape.grid=%d" % g] + end)
        if s is None:
            rows.append([g, balls, haus / 2, vol, "failed: " + err] + ["–"] * 4)
            continue
        per_step = s["wall_time_s"] / max(s["steps"], 1)
        per_sim = s["wall_time_s"] / max(s["simulated_time_s"], 1e-30)
        phi = err_phi = None
        if not quick:
            # The bed is a few cubes deep: a region 1 bounding diameter from the
            # side walls and the floor, up to 1 diameter below the top of the bed.
            region, thin = clump_region(build, out)
            phi, err_phi, why = (None, None, thin) if thin else analyze_phi(build, out, region)
            if why:
                phi = "no φ: " + why
        rows.append([g, balls, haus / 2, vol, s["particles_start"], s["time_step_s"], per_step * 1e3, per_sim,
                     phi, err_phi])
        if isinstance(phi, float):
            pts.append((g, balls, per_sim, phi, err_phi, haus / 2, vol))
    rep.add("""
## 3. Clump resolution

A cube (cases/pour_clumps/cube.off) decomposed into balls by `grains clump
--grid N` (docs/decomposition.md): ball count, Hausdorff distance from the
cube (relative to its side) and error of the union's volume, as the
command reports them. Then `pour_clumps_small.yaml` (this folder): 60
cubes of bounding radius 0.8 mm dropped from up to 15 mm into a 6 mm × 6 mm box, %s; the
time step is 0.2 T_R of the smallest ball, so a finer decomposition costs
per step (more balls) and in steps. Packing fraction: `grains analyze`
(Monte Carlo union volume, ± its 1σ sampling error) in a box 1.6 mm from
the side walls and the floor up to 1.6 mm below the free surface. One run
per grid (seed 7): the ± is the Monte Carlo error only, not the spread
between pours (0.004–0.01 for the sphere pour of section 2); %s.
""" % ("5 ms (quick)" if quick else "0.12 s", env_line))
    rep.add(table(["grid N", "balls per cube", "Hausdorff / side", "volume error %", "balls in scene",
                   "dt s", "ms per step", "wall s per simulated s", "φ", "± (MC)"], rows) + "\n")
    if pts:
        fig, axes = plt.subplots(1, 2, figsize=(11, 4))
        ax = axes[0]
        ax.plot([q[1] for q in pts], [q[5] for q in pts], "o-", label="Hausdorff / side")
        ax.plot([q[1] for q in pts], [q[6] / 100 for q in pts], "s-", label="volume error / 100 %")
        ax.set_xscale("log")
        ax.set_xlabel("balls per cube")
        ax.legend()
        ax.set_title("shape error against ball count")
        ax = axes[1]
        ax.errorbar([q[2] for q in pts], [q[3] for q in pts], yerr=[q[4] for q in pts], fmt="o-", capsize=3)
        for q in pts:
            ax.annotate("N=%d" % q[0], (q[2], q[3]), fontsize=7, textcoords="offset points", xytext=(3, 3))
        ax.set_xscale("log")
        ax.set_xlabel("wall s per simulated s")
        ax.set_ylabel("poured φ")
        ax.set_title("poured cubes: φ against cost")
        rep.figure(fig, "clumps.png", "clump resolution: shape error, cost and packing")


def clump_region(build, out):
    """The analysis box of the clump pour: 1.6 mm (a bounding diameter) from
    the side walls and the floor, up to 1.6 mm below the free surface (where
    `grains analyze --margin 0` puts it)."""
    tmp = os.path.join(out, "analysis_surface")
    sh([os.path.join(build, "grains"), "analyze", out, "-o", tmp, "--no-plots", "--margin", "0"])
    with open(os.path.join(tmp, "analysis.json")) as f:
        top = json.load(f)["region"]["max"][2]
    # (region, None), or (None, why) when the bed is too thin for a bulk box:
    # 60 clumps make a bed 2-3 cubes deep, and a box reaching into the free
    # surface or above the bed gives no packing fraction (bench/RESULTS.md,
    # "Clump pours against the resolution").
    if top - 0.0016 < 0.0016 + 0.0016:
        return None, "bed too thin: surface at %.1f mm, a bulk box needs 4.8" % (top * 1e3)
    return [0.0016, 0.0016, 0.0016, 0.006 - 0.0016, 0.006 - 0.0016, top - 0.0016], None




# ---------------------------------------------------------------- 4: NFFT


def section_nfft(rep, build, quick, env_line):
    exe = os.path.join(build, "bench", "accuracy_vs_time", "accuracy_nfft")
    filt = "BM_FieldTolerance/(4|8)/|BM_TruncatedQuery/(64|4096)$" if quick else "BM_FieldTolerance|BM_TruncatedQuery"
    reps = 1 if quick else 3
    r = gbench(exe, filt, reps, 0.01 if quick else 0.1, quick)
    rep.add("""
## 4. NFFT: tolerance and truncated modes

`accuracy_nfft` (this folder), one thread. **Field**: the translational
overlap field (contact/correlation/overlap_field.hpp) of a 4-ball clump
against a random bed of 100,000 balls on a 48³ grid of translations, at NUFFT
tolerance ε; error = max |V − V_ref| / max V_ref against the same field at
ε = 1e-13 (the NUFFT error only; the truncation to the grid's modes is the
same for both, docs/nfft.md measures it). **Query**: one overlap volume of
two 20-ball clumps from the m′ dominant modes (truncated_overlap.hpp, the
seed's Figs. 7–9; spectra at ε = 1e-9 with |m| ≤ 32), error against the
exact sum of lens volumes over 64 translations (rms and max, relative to
the largest overlap). %s.
""" % env_line)
    rows, fx, fy = [], [], []
    for name, d in sorted(r.items(), key=lambda kv: int(kv[0].split("/")[1])):
        if name.startswith("BM_FieldTolerance/"):
            k = int(name.split("/")[1])
            rows.append(["1e-%d" % k, d["max_err_rel"], d["seconds"] * 1e3])
            fx.append(d["seconds"] * 1e3)
            fy.append(max(d["max_err_rel"], 1e-17))
    rep.add(table(["NUFFT ε", "field error (max, relative)", "ms per field"], rows) + "\n")
    rows, qx, qy, qm = [], [], [], []
    for name, d in sorted(r.items(), key=lambda kv: int(kv[0].split("/")[1])):
        if name.startswith("BM_TruncatedQuery/"):
            m = int(name.split("/")[1])
            rows.append([m, d["rms_err_rel"], d["max_err_rel"], d["seconds"] * 1e9, int(d["modes_total"])])
            qx.append(d["seconds"] * 1e9)
            qy.append(d["rms_err_rel"])
            qm.append(m)
    rep.add(table(["m′", "rms error (relative)", "max error (relative)", "ns per query", "modes stored"], rows) + "\n")
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    axes[0].loglog(fx, fy, "o-")
    axes[0].set_xlabel("ms per field")
    axes[0].set_ylabel("max relative error")
    axes[0].set_title("overlap field: NUFFT tolerance")
    axes[1].loglog(qx, qy, "s-")
    for x, y, m in zip(qx, qy, qm):
        axes[1].annotate("%d" % m, (x, y), fontsize=7, textcoords="offset points", xytext=(3, 3))
    axes[1].set_xlabel("ns per query")
    axes[1].set_ylabel("rms relative error")
    axes[1].set_title("truncated query: m′ (labels)")
    rep.figure(fig, "nfft.png", "NFFT errors against time")


# ---------------------------------------------------------------- 5: skin


def section_skin(rep, build, quick, env_line):
    exe = os.path.join(build, "bench", "accuracy_vs_time", "accuracy_skin")
    case = os.path.join(HERE, "pour_small.yaml")
    skins = ["0.1", "0.02", "0.4"] if quick else ["0.1", "0.02", "0.05", "0.2", "0.4", "0.8"]
    end = ["--set", "time.end=0.005"] if quick else ["--set", "time.end=0.06"]
    reps = ["--reps", "1" if quick else "3"]
    res = {}
    for det in ("true", "false"):
        out = sh([exe, case, "--set", "parallel.deterministic=" + det] + end + reps + skins)[1]
        res[det] = [json.loads(line) for line in out.splitlines() if line.strip()]
    rep.add("""
## 5. Neighbour search: skin and rebuild frequency

`accuracy_skin` (this folder) runs `pour_small.yaml` (seed 1) for %s of
simulated time once per skin (neighbor.skin, a fraction of the largest
diameter; the list is rebuilt when a particle has moved half the skin) and
compares the final positions and velocities with the run at skin 0.1.
With `parallel.deterministic: true` each particle sums its contact forces
in the order of its partners' global ids, so the result cannot depend on
which non-touching pairs the list holds: bitwise identical at every skin
(checked). With the default serial summation (list order) the sums'
round-off depends on the list, and the chaotic dynamics of the pour
amplifies it: the last column shows how far the particles end up. Wall:
the time loop, median of %s; %s.
""" % ("5 ms (quick)" if quick else "0.06 s", reps[1], env_line))
    rows = []
    for a, b in zip(res["true"], res["false"]):
        rows.append([a["skin"], a["builds"], a["wall_median_s"], "yes" if a["identical"] else "NO",
                     b["wall_median_s"], b["max_dx_over_r"]])
    rep.add(table(["skin (× d)", "builds", "wall s (deterministic)", "identical to skin 0.1",
                   "wall s (list order)", "max Δx / r (list order)"], rows) + "\n")
    fig, ax = plt.subplots(figsize=(6, 4))
    xs = [a["skin"] for a in res["true"]]
    order = sorted(range(len(xs)), key=lambda i: xs[i])
    ax.plot([xs[i] for i in order], [res["true"][i]["wall_median_s"] for i in order], "o-", label="wall s (deterministic)")
    ax.plot([xs[i] for i in order], [res["false"][i]["wall_median_s"] for i in order], "s-", label="wall s (list order)")
    ax.set_xscale("log")
    ax.set_xlabel("skin / d")
    ax.set_ylabel("wall s")
    ax2 = ax.twinx()
    ax2.plot([xs[i] for i in order], [res["true"][i]["builds"] for i in order], "k:", label="builds")
    ax2.set_ylabel("neighbour builds")
    ax.legend(loc="upper center", fontsize=8)
    ax.set_title("skin against time (result unchanged)")
    rep.figure(fig, "skin.png", "neighbour skin against wall time")
    return res


# ---------------------------------------------------------------- main


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs"), help="folder of accuracy-vs-time.md")
    ap.add_argument("--quick", action="store_true", help="a couple of points per sweep (smoke test)")
    ap.add_argument("--only", default="1,2,3,4,5", help="sections to run, e.g. 1,4")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    for exe in ("grains", "bench/accuracy_vs_time/accuracy_pw85", "bench/accuracy_vs_time/accuracy_nfft",
                "bench/accuracy_vs_time/accuracy_skin", "bench/accuracy_vs_time/accuracy_impact"):
        if not os.path.exists(os.path.join(build, exe)):
            sys.exit("missing %s: build it first (bash bench/accuracy_vs_time/run.sh builds everything)" % exe)
    os.makedirs(a.out, exist_ok=True)
    rep = Report(a.out, "accuracy-vs-time", a.quick)
    m = machine()
    start = datetime.datetime.now(datetime.timezone.utc)
    t0 = time.time()
    load0 = os.getloadavg()
    git = "?"
    try:
        git = sh(["git", "-C", ROOT, "describe", "--always", "--dirty"])[1].strip()
    except Exception:
        pass
    env_line = "machine: %s, %s CPUs (%s thread(s) per core), shared; one thread" % (
        m["model"], m["cpus"], m["threads_per_core"])
    only = set(int(x) for x in a.only.split(",") if x)
    work = tempfile.mkdtemp(prefix="grains_accuracy_")
    timings = {}
    try:
        sections = [(1, lambda: section_pw85(rep, build, a.quick, env_line)),
                    (2, lambda: section_integration(rep, build, a.quick, env_line, work)),
                    (3, lambda: section_clumps(rep, build, a.quick, env_line, work)),
                    (4, lambda: section_nfft(rep, build, a.quick, env_line)),
                    (5, lambda: section_skin(rep, build, a.quick, env_line))]
        for k, f in sections:
            if k in only:
                s0 = time.time()
                f()
                timings[k] = time.time() - s0
                print("section %d: %.0f s" % (k, timings[k]), file=sys.stderr)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    total = time.time() - t0
    head = """# Accuracy against time

What accuracy costs in time, measured: the PW85 contact function, time
integration (velocity Verlet and SUNDIALS ARKODE), clump resolution, the
NFFT overlap fields, and the neighbour skin. Written by
`bash bench/accuracy_vs_time/run.sh` (or `/usr/bin/python3
bench/accuracy_vs_time/run.py`): every number and figure below comes from
the runs it made%s.

- **Machine**: `lscpu` model name "%s", %s CPUs, %s thread(s) per core;
  shared with other engineers' builds (load average %.1f at the start,
  %.1f at the end), so wall times carry some noise: each figure is a
  median over repetitions as stated per table.
- **Date**: %s UTC; grains %s (g++ Release); SUNDIALS %s.
- **Run time**: %.0f s in all (%s).
""" % (" (quick smoke mode: a couple of points per sweep)" if a.quick else "",
       m["model"], m["cpus"], m["threads_per_core"], load0[0], os.getloadavg()[0],
       start.strftime("%Y-%m-%d %H:%M"), git, sundials_version(), total,
       ", ".join("section %d %.0f s" % (k, v) for k, v in sorted(timings.items())))
    path = os.path.join(a.out, "accuracy-vs-time.md")
    with open(path, "w") as f:
        f.write(head + "\n" + "\n".join(rep.parts))
    print(path)


def sundials_version():
    try:
        out = sh(["dpkg-query", "-W", "-f=${Version}", "libsundials-dev"])[1]
        return out.strip() or "?"
    except Exception:
        return "?"


if __name__ == "__main__":
    main()
