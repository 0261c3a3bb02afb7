"""Reading a finished run's output into numpy.

    frames = grains.output.read_frames("out/pour")
    last = frames[-1]
    last.time, last.points.shape, last["velocity"], last["radius"]

Frames are read with VTK's Python package (Debian python3-vtk9, which
libvtk9-dev brings); summary.json and the CSV series need nothing more.
"""
import csv
import json
import os
import xml.etree.ElementTree as ET

import numpy as np


class Frame:
    """One frame of particles.pvd: its time, file, points (n, 3) and point arrays by name."""

    def __init__(self, time, file, points, arrays):
        self.time, self.file, self.points, self.arrays = time, file, points, arrays

    def __getitem__(self, name):
        return self.arrays[name]

    def keys(self):
        return self.arrays.keys()

    def __repr__(self):
        return "<grains.output.Frame t=%g s, %d points, %s>" % (self.time, len(self.points), sorted(self.arrays))


def series(out_dir, name="particles"):
    """The (time, file) entries of OUT/<name>.pvd, in time order."""
    pvd = os.path.join(os.fspath(out_dir), name + ".pvd")
    if not os.path.exists(pvd):
        raise FileNotFoundError("%s: no such series (was the run's VTK output on?)" % pvd)
    root = ET.parse(pvd).getroot()
    entries = [(float(d.get("timestep")), os.path.join(os.path.dirname(pvd), d.get("file")))
               for d in root.iter("DataSet")]
    return sorted(entries)


def read_frame(file, time=float("nan")):
    """A .vtu or .pvtu file (grains, bodies) or a .vtp file (walls) as a Frame."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import (vtkXMLPolyDataReader, vtkXMLPUnstructuredGridReader,
                                     vtkXMLUnstructuredGridReader)
    readers = {".pvtu": vtkXMLPUnstructuredGridReader, ".vtu": vtkXMLUnstructuredGridReader,
               ".vtp": vtkXMLPolyDataReader}
    ext = os.path.splitext(file)[1]
    if ext not in readers:
        raise ValueError("%s: not a frame (.vtu, .pvtu or .vtp)" % file)
    reader = readers[ext]()
    reader.SetFileName(file)
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or (grid.GetNumberOfPoints() == 0 and not os.path.exists(file)):
        raise OSError("%s: cannot read the frame" % file)
    pts = grid.GetPoints()
    points = vtk_to_numpy(pts.GetData()).copy() if pts is not None else np.zeros((0, 3))
    pd = grid.GetPointData()
    arrays = {pd.GetArrayName(k): vtk_to_numpy(pd.GetArray(k)).copy() for k in range(pd.GetNumberOfArrays())}
    return Frame(time, file, points, arrays)


def read_frames(out_dir, name="particles"):
    """Every frame of OUT/<name>.pvd (particles, bodies or walls), in time order."""
    return [read_frame(f, t) for t, f in series(out_dir, name)]


def read_summary(out_dir):
    """OUT/summary.json as a dict."""
    with open(os.path.join(os.fspath(out_dir), "summary.json")) as f:
        return json.load(f)


def read_csv(file):
    """A CSV series (solid_fraction.csv, wall_loads.csv, stress.csv, ...) as a dict of numpy columns."""
    with open(os.fspath(file), newline="") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    if not rows:
        raise ValueError("%s: empty" % file)
    head, body = rows[0], rows[1:]
    cols = {}
    for k, h in enumerate(head):
        try:
            cols[h] = np.array([float(r[k]) for r in body])
        except ValueError:
            cols[h] = np.array([r[k] for r in body])
    return cols
