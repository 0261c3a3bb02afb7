#!/usr/bin/python3
"""Rows of the clump-resolution table (accuracy-vs-time section 3) for any
mesh, without rerunning the whole report: for each grid, `grains clump`
(n3, eps, Hausdorff distance, volume error, decomposition time), then the
fixed pour of pour_clumps_small.yaml (60 clumps of bounding radius 0.8 mm
into a 6 mm x 6 mm box, 0.12 s, seed 7) with that mesh and grid: DEM cost
per step and the poured packing fraction (`grains analyze`, Monte Carlo
union volume, the region of section 3, when the bed is deep enough for it;
it rarely is: bench/RESULTS.md). Prints a Markdown table.

    /usr/bin/python3 bench/accuracy_vs_time/clump_rows.py --mesh cases/pour_clumps/bunny.off --grids 8,12,16
"""
import argparse
import datetime
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run  # noqa: E402  (its helpers: sh, pour_run, analyze_phi, clump_region, machine, table)


def decomposition(build, mesh, grid, work):
    out = os.path.join(work, "clump_%d.yaml" % grid)
    txt = run.sh([os.path.join(build, "grains"), "clump", mesh, "--grid", str(grid), "-o", out])[1]
    n3 = int(re.search(r"n3 = (\d+)", txt).group(1))
    eps = float(re.search(r"eps = ([0-9.eE+-]+)", txt).group(1))
    haus = float(re.search(r"^hausdorff\s+([0-9.eE+-]+)", txt, re.M).group(1))
    vol = float(re.search(r"error ([+-]?[0-9.eE+-]+) %", txt).group(1))
    t = float(re.search(r"decomposition ([0-9.eE+-]+) s", txt).group(1))
    # The grid's cube has edge 2L = the mesh's longest extent, eps = sqrt(3) L / N.
    extent = 2 * eps * grid / 3 ** 0.5
    return n3, eps / extent, haus / extent, vol, t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(run.ROOT, "build"))
    ap.add_argument("--mesh", required=True)
    ap.add_argument("--grids", default="8,12,16")
    ap.add_argument("--work", default="/tmp/grains_clump_rows")
    a = ap.parse_args()
    build = os.path.abspath(a.build)
    mesh = os.path.abspath(a.mesh)
    os.makedirs(a.work, exist_ok=True)
    case = os.path.join(run.HERE, "pour_clumps_small.yaml")
    m = run.machine()
    git = run.sh(["git", "-C", run.ROOT, "describe", "--always", "--dirty"])[1].strip()
    print("%s, %s, grains %s, machine: %s, %s CPUs, shared (load average %.1f at the start)" % (
        os.path.basename(mesh), datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"), git,
        m["model"], m["cpus"], os.getloadavg()[0]), flush=True)
    rows = []
    for g in [int(x) for x in a.grids.split(",")]:
        n3, eps, haus, vol, t = decomposition(build, mesh, g, a.work)
        out = os.path.join(a.work, "%s_%d" % (os.path.splitext(os.path.basename(mesh))[0], g))
        s, err = run.pour_run(build, case, out, ["particles.0.shape.mesh=" + mesh, "particles.0.shape.grid=%d" % g])
        if s is None:
            rows.append([g, n3, eps, haus, vol, t, "failed: " + err] + ["–"] * 6)
            continue
        region, thin = run.clump_region(build, out)
        phi, err_phi, why = (None, None, thin) if thin else run.analyze_phi(build, out, region)
        rows.append([g, n3, eps, haus, vol, t, s["particles_start"], s["time_step_s"],
                     1e3 * s["wall_time_s"] / max(s["steps"], 1), s["wall_time_s"] / s["simulated_time_s"],
                     s["lost_particles"], phi if why is None else "no φ: " + why, err_phi])
        print("grid %d done" % g, file=sys.stderr, flush=True)
    print(run.table(["grid N", "n₃", "ε / extent", "Hausdorff / extent", "volume error %", "decomposition s",
                     "balls in scene", "dt s", "ms per step", "wall s per simulated s", "lost", "φ", "± (MC)"],
                    rows))
    print("(load average %.1f at the end)" % os.getloadavg()[0])


if __name__ == "__main__":
    main()
