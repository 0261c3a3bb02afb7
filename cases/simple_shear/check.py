#!/usr/bin/env python3
"""Checks the simple_shear results (OUT/mu_I.csv, OUT/fit.json from analyze.py).

check.py OUT point   the CI point (I = 0.1): the cell held its pressure
                     (1000 Pa to 3 %), and mu and phi lie in the bands of
                     the dense-flow rheology at I = 0.1 (see README.md);
check.py OUT sweep   the long sweep: mu rises with I (beyond the error
                     bars), phi falls, and the fitted mu_s, mu_2, I_0, phi_c
                     lie in the bands of README.md.
Exits 1 with the failures listed."""
import csv
import json
import os
import sys

out, mode = sys.argv[1], sys.argv[2]
rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(os.path.join(out, "mu_I.csv")))]
bad = []


def band(name, value, lo, hi):
    ok = lo <= value <= hi
    print("%-8s %.4f  in [%g, %g]: %s" % (name, value, lo, hi, "ok" if ok else "NO"))
    if not ok:
        bad.append(name)


if mode == "point":
    q = min(rows, key=lambda r: abs(r["I"] - 0.1))
    band("pressure", q["pressure_Pa"] / 1000, 0.97, 1.03)
    band("I", q["I"], 0.095, 0.105)
    band("mu", q["mu"], 0.39, 0.47)
    band("phi", q["solid_fraction"], 0.56, 0.59)
else:
    for a, b in zip(rows, rows[1:]):
        if not b["mu"] + 2 * b["mu_err"] > a["mu"] - 2 * a["mu_err"]:
            bad.append("mu falls from I = %g to %g" % (a["I"], b["I"]))
        if not b["solid_fraction"] < a["solid_fraction"] + 2 * (a["solid_fraction_err"] + b["solid_fraction_err"]) + 1e-3:
            bad.append("phi rises from I = %g to %g" % (a["I"], b["I"]))
    fit = json.load(open(os.path.join(out, "fit.json")))
    band("mu_s", fit["mu_s"], 0.30, 0.42)
    band("mu_2", fit["mu_2"], 0.50, 1.0)
    band("I_0", fit["I_0"], 0.05, 1.0)
    band("phi_c", fit["phi_c"], 0.57, 0.61)
    band("b", fit["b"], 0.1, 0.6)
if bad:
    print("check.py: failed: " + ", ".join(bad))
    sys.exit(1)
print("check.py: all within the bands")
