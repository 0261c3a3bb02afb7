"""Runs a script with pvpython from a python3-paraview unpacked beside the
build (.ci/setup: Debian's python3-paraview and python3-vtk9, which
libvtk9-dev needs, both ship `vtkmodules`, so the two cannot be installed
together). pvpython puts the system's site folder first on sys.path; this
puts the unpacked one ($GRAINS_PV_SITE) before it, then runs the script as
pvpython would:

    pvpython pvpython_launch.py SCRIPT [ARGS...]
"""
import os
import runpy
import sys

site = os.environ.get("GRAINS_PV_SITE")
if site:
    sys.path.insert(0, site)
sys.argv = sys.argv[1:]
runpy.run_path(sys.argv[0], run_name="__main__")
