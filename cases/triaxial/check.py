#!/usr/bin/env python3
"""Checks of the triaxial test (tests/regression): what a dense and a loose
sample of the same spheres must show in drained compression.

    python3 check.py dense DENSE_OUT            the dense sample's peak (default suite: shear to 10 %)
    python3 check.py both DENSE_OUT LOOSE_OUT   both preparations to 33 % axial strain (label long)

DENSE_OUT and LOOSE_OUT are run.sh's output folders (consolidate/, shear/).
The dense sample was consolidated frictionless (PREP_FRICTION=0): at its
peak it must dilate and its friction angle must stand well above the
critical state; the loose one contracts to that same critical state. Both
must end at the same friction angle and solid fraction: the critical state
does not depend on the initial density. The bands are those of
cases/triaxial/README.md.
"""
import csv
import json
import os
import sys


def solid_fraction(out, stage):
    with open(os.path.join(out, stage, "stress.csv")) as f:
        rows = list(csv.DictReader(f))
    return float(rows[-1]["solid_fraction"])


def load(out):
    with open(os.path.join(out, "shear", "triaxial.json")) as f:
        r = json.load(f)
    r["phi_start"] = solid_fraction(out, "consolidate")
    r["phi_end"] = solid_fraction(out, "shear")
    return r


failures = []


def expect(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def main():
    mode = sys.argv[1]
    d = load(sys.argv[2])
    print("dense:", json.dumps(d))
    expect(d["phi_start"] >= 0.60, "dense sample consolidated to solid fraction %.4f >= 0.60" % d["phi_start"])
    expect(24 <= d["peak_friction_angle_deg"] <= 32,
           "dense peak friction angle %.2f deg in [24, 32]" % d["peak_friction_angle_deg"])
    expect(d["peak_axial_strain"] <= 0.08, "dense peak at axial strain %.3f <= 0.08" % d["peak_axial_strain"])
    expect(d["dilatancy_at_peak"] <= -0.2, "dense sample dilates at its peak: d eps_v/d eps_a = %.3f <= -0.2" %
           d["dilatancy_at_peak"])
    if mode == "both":
        lo = load(sys.argv[3])
        print("loose:", json.dumps(lo))
        expect(d["phi_start"] - lo["phi_start"] >= 0.03, "dense starts denser than loose by %.4f >= 0.03" %
               (d["phi_start"] - lo["phi_start"]))
        expect(d["peak_friction_angle_deg"] - d["critical_friction_angle_deg"] >= 4,
               "dense peak above its critical state by %.2f >= 4 deg" %
               (d["peak_friction_angle_deg"] - d["critical_friction_angle_deg"]))
        expect(lo["peak_friction_angle_deg"] - lo["critical_friction_angle_deg"] <= 3.5,
               "loose sample has no marked peak: %.2f <= 3.5 deg above its critical state" %
               (lo["peak_friction_angle_deg"] - lo["critical_friction_angle_deg"]))
        expect(abs(d["critical_friction_angle_deg"] - lo["critical_friction_angle_deg"]) <= 1.5,
               "one critical state: dense %.2f and loose %.2f deg within 1.5" %
               (d["critical_friction_angle_deg"], lo["critical_friction_angle_deg"]))
        expect(abs(d["phi_end"] - lo["phi_end"]) <= 0.01,
               "one critical solid fraction: dense %.4f and loose %.4f within 0.01" % (d["phi_end"], lo["phi_end"]))
        for name, r in (("dense", d), ("loose", lo)):
            expect(abs(r["dilatancy_last_quarter"]) <= 0.05, "%s volume steady over the last quarter: %.3f within 0.05" %
                   (name, r["dilatancy_last_quarter"]))
            expect(16 <= r["critical_friction_angle_deg"] <= 24, "%s critical-state angle %.2f deg in [16, 24]" %
                   (name, r["critical_friction_angle_deg"]))
    if failures:
        sys.exit("%d check(s) failed" % len(failures))


if __name__ == "__main__":
    main()
