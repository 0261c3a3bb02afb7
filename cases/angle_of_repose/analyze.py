#!/usr/bin/env python3
"""The angle of repose of the heap a lifted cylinder leaves (cases/angle_of_repose).

analyze.py RUN [PNG]: reads RUN's last frame (particles.pvd), takes the heap's
axis at the grains' mean x, y, and in rings of one mean diameter around it
the highest grain top (z + r); the heap's slope is the least-squares line of
those tops against the ring radius between 25 % and 75 % of the heap's
radius (the radius where the tops fall to two diameters: beyond, a few
scattered grains), its angle atan(-slope). Prints and writes RUN/heap.json
(the angle, the line's R^2, the heap's radius and height, the grains' kinetic
energy per grain to show that the heap is at rest); PNG with matplotlib.
"""
import glob
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy


def last_frame(run):
    pvd = ET.parse(os.path.join(run, "particles.pvd")).getroot()
    files = [d.get("file") for d in pvd.iter("DataSet")]
    return os.path.join(run, files[-1])


def main():
    run = sys.argv[1]
    r = vtk.vtkXMLUnstructuredGridReader()
    r.SetFileName(last_frame(run))
    r.Update()
    o = r.GetOutput()
    x = vtk_to_numpy(o.GetPoints().GetData())
    pd = o.GetPointData()
    rad = vtk_to_numpy(pd.GetArray("radius"))
    v = vtk_to_numpy(pd.GetArray("velocity"))
    d = 2 * rad.mean()
    c = x[:, :2].mean(axis=0)
    rr = np.hypot(x[:, 0] - c[0], x[:, 1] - c[1])
    top = x[:, 2] + rad
    rings = np.arange(0, rr.max() + d, d)
    ring_r, ring_top = [], []
    for a, b in zip(rings[:-1], rings[1:]):
        sel = (rr >= a) & (rr < b)
        if sel.sum() >= 3:
            ring_r.append(0.5 * (a + b))
            ring_top.append(top[sel].max())
    ring_r, ring_top = np.array(ring_r), np.array(ring_top)
    edge = ring_r[ring_top > 2 * d].max()  # the heap's radius
    fit = (ring_r >= 0.25 * edge) & (ring_r <= 0.75 * edge)
    slope, icpt = np.polyfit(ring_r[fit], ring_top[fit], 1)
    pred = slope * ring_r[fit] + icpt
    r2 = 1 - ((ring_top[fit] - pred) ** 2).sum() / ((ring_top[fit] - ring_top[fit].mean()) ** 2).sum()
    angle = math.degrees(math.atan(-slope))
    m = 4 / 3 * math.pi * rad ** 3 * 2500
    res = {"angle_deg": angle, "r2": r2, "heap_radius_m": float(edge), "heap_height_m": float(ring_top.max()),
           "rings_fitted": int(fit.sum()), "grains": int(len(x)),
           "kinetic_energy_per_grain_J": float((0.5 * m * (v ** 2).sum(axis=1)).mean()),
           "frame": os.path.basename(last_frame(run))}
    with open(os.path.join(run, "heap.json"), "w") as f:
        json.dump(res, f, indent=1)
    for k, val in res.items():
        print("%-28s %s" % (k, val))
    if len(sys.argv) > 2:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(10, 3.8))
        ax[0].plot(rr * 1e3, x[:, 2] * 1e3, ".", ms=1.5, color="gray", label="grains")
        ax[0].plot(ring_r * 1e3, ring_top * 1e3, "o", ms=3, label="highest top per ring")
        ax[0].plot(ring_r[fit] * 1e3, pred * 1e3, "-", label="slope %.1f deg" % angle)
        ax[0].set_xlabel("distance from the heap's axis (mm)")
        ax[0].set_ylabel("height (mm)")
        ax[0].set_aspect("equal")
        ax[0].legend(fontsize=8)
        ax[1].scatter(x[:, 0] * 1e3, x[:, 1] * 1e3, s=2, c=x[:, 2], cmap="viridis")
        ax[1].set_aspect("equal")
        ax[1].set_xlabel("x (mm)")
        ax[1].set_ylabel("y (mm), coloured by height")
        fig.suptitle("heap from a lifted cylinder: friction 0.5, rolling friction 0.1")
        fig.tight_layout()
        fig.savefig(sys.argv[2], dpi=110)


if __name__ == "__main__":
    main()
