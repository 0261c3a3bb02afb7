"""Opens a run's view.py (the ParaView state grains writes beside
particles.pvd) with pvpython under Xvfb and checks what it shows: the
picture is not blank, and the glyphs' bounds are the grains' own (centres
+- radius for spheres and clump balls, the exact ellipsoid extents
sqrt((T^2)_kk) of the shape tensor T for ellipsoids).

    python3 check_view.py GRAINS OUTDIR_ROOT NAME CASE [--set k=v ...]

Run by ctest (tests/paraview/CMakeLists.txt) with Debian's python3 (vtk,
numpy) and pvpython from python3-paraview.
"""
import json
import os
import shutil
import subprocess
import sys
import time

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader


def last_frame(out):
    import xml.etree.ElementTree as ET
    ds = sorted((float(d.get("timestep")), d.get("file")) for d in ET.parse(os.path.join(out, "particles.pvd")).getroot().iter("DataSet"))
    r = vtkXMLUnstructuredGridReader()
    r.SetFileName(os.path.join(out, ds[-1][1]))
    r.Update()
    g = r.GetOutput()
    pd = g.GetPointData()
    arrays = {pd.GetArrayName(k): vtk_to_numpy(pd.GetArray(k)) for k in range(pd.GetNumberOfArrays())}
    return ds[-1][0], vtk_to_numpy(g.GetPoints().GetData()), arrays


def expected_bounds(x, a):
    if "shape_tensor" in a:
        T = a["shape_tensor"].reshape(-1, 3, 3)
        half = np.sqrt(np.einsum("nij,nji->ni", T, T))  # (T T)_kk, T symmetric
    else:
        half = np.repeat(a["radius"][:, None], 3, axis=1)
    lo, hi = (x - half).min(axis=0), (x + half).max(axis=0)
    return np.column_stack([lo, hi]).ravel(), half.max()


def main(argv):
    grains, root, name, case = argv[1:5]
    sets = argv[5:]
    out = os.path.join(root, name)
    shutil.rmtree(out, ignore_errors=True)
    subprocess.run([grains, "run", case, "-o", out, "-q"] + sets, check=True)
    view = os.path.join(out, "view.py")
    assert os.path.exists(view), "no view.py beside particles.pvd"
    png = os.path.join(out, "view.png")
    pvpython = os.environ.get("GRAINS_PVPYTHON", "pvpython")
    launch = os.path.join(os.path.dirname(os.path.abspath(__file__)), "pvpython_launch.py")
    # A display number of its own (tests run side by side), and another try
    # when the X server went away under pvpython (xvfb-run can hand over a
    # display whose previous server is still shutting down), after a pause
    # that grows: on 2026-12-07 a CI run lost it three times within 4 s while
    # the other ParaView test started its own.
    tries = 5
    for attempt in range(tries):
        display = str(100 + (os.getpid() * 7 + attempt * 131) % 800)
        pv = subprocess.run(["xvfb-run", "-a", "-n", display, "-s", "-screen 0 1280x1024x24", pvpython, launch, view,
                             "--bounds", "--screenshot", png, "--size", "640x480"],
                            capture_output=True, text=True, timeout=300)
        if "bad X server connection" not in pv.stdout + pv.stderr:
            break
        if attempt + 1 < tries:
            print("pvpython lost its X server (display %s); trying again" % display)
            time.sleep(1 + 2 * attempt)
    lines = [l for l in pv.stdout.splitlines() if l.startswith("{")]
    if pv.returncode != 0 or not lines:
        sys.exit("pvpython failed (%d):\n%s\n%s" % (pv.returncode, pv.stdout[-3000:], pv.stderr[-3000:]))
    shown = json.loads(lines[-1])
    t, x, a = last_frame(out)
    assert abs(shown["time"] - t) <= 1e-9 * max(1.0, t), (shown["time"], t)
    glyphs = [k for k in shown["shown"] if k in ("spheres", "ellipsoids", "clump balls")]
    assert len(glyphs) == 1, shown
    kind = glyphs[0]
    if "shape_tensor" in a:
        assert kind == "ellipsoids", kind
    elif "body" in a:
        assert kind == "clump balls", kind
    else:
        assert kind == "spheres", kind
    want, size = expected_bounds(x, a)
    got = np.array(shown["shown"][kind])
    # Glyphs are tessellated: their extreme points lie within 3 % of a radius
    # inside the true surface (resolutions 16-24 around, 12 from pole to pole).
    err = np.abs(got - want).max()
    print("%s: %d grains at t = %g s, bounds %s, expected %s, largest difference %.3g m (%.2f %% of the largest "
          "half-extent)" % (kind, len(x), t, np.round(got, 6), np.round(want, 6), err, 100 * err / size))
    assert err <= 0.03 * size, "the glyphs' bounds are not the grains'"
    # The picture: not blank (a picture of the background alone is one colour).
    r = vtkPNGReader()
    r.SetFileName(png)
    r.Update()
    img = vtk_to_numpy(r.GetOutput().GetPointData().GetScalars()).reshape(-1, r.GetOutput().GetNumberOfScalarComponents())
    rgb = img[:, :3].astype(int)
    background = np.median(rgb, axis=0)
    differ = (np.abs(rgb - background).sum(axis=1) > 30).mean()
    print("picture %s: %d pixels, %.1f %% differ from the background" % (png, len(rgb), 100 * differ))
    assert differ > 0.01, "the picture is blank"
    for k in shown["shown"]:
        print("shown: %s" % k)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
