#include "io/output/paraview_state.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>

namespace grains::io {

const char* paraview_state_script() {
  return R"PV(# ParaView state of a grains run, written by grains beside particles.pvd.
#
#   paraview --script=view.py          open the run in the ParaView window
#   pvpython view.py --screenshot a.png [--size 1200x900] [--time T]
#                                      an offscreen picture (last frame by default)
#   pvpython view.py --bounds          print what is shown, with its bounds, as JSON
#
# Spheres are sphere glyphs of their radius, ellipsoids tensor glyphs of their
# shape tensor (the exact ellipsoid), clump balls spheres coloured by their
# body, walls and meshes surfaces, solid-fraction fields volumes. It reads the
# files next to it, so the output folder can be moved or copied whole.
import json
import os
import sys

from paraview.simple import *  # noqa: F401,F403

try:
    HERE = os.path.dirname(os.path.abspath(__file__))
except NameError:  # run by paraview --script in some versions: the folder is the working one
    HERE = os.getcwd()


def _path(name):
    p = os.path.join(HERE, name)
    return p if os.path.exists(p) else None


def _arrays(source):
    source.UpdatePipelineInformation()
    return set(source.PointData.keys())


def show_run(view=None):
    """Loads the run into `view` (the active one by default); returns {name: proxy} of what it shows."""
    view = view or GetActiveViewOrCreate("RenderView")
    shown = {}
    p = _path("particles.pvd")
    if p:
        reader = PVDReader(registrationName="particles.pvd", FileName=p)
        arrays = _arrays(reader)
        if "shape_tensor" in arrays:
            # Tensor glyphs: a unit-diameter sphere stretched by the tensor's
            # eigenvalues (the semi-axes) along its eigenvectors; x2 for radii.
            speed = Calculator(registrationName="speed", Input=reader, ResultArrayName="speed",
                               Function="mag(velocity)")
            g = TensorGlyph(registrationName="ellipsoids", Input=speed, GlyphType="Sphere")
            g.Tensors = ["POINTS", "shape_tensor"]
            g.ScaleFactor = 2.0
            g.GlyphType.ThetaResolution = 24
            g.GlyphType.PhiResolution = 12
            g.Scalars = ["POINTS", "speed"]
            g.ColorGlyphs = 1
            g.Colorby = "input scalars"
            name, colour = "ellipsoids", ("speed", None)
        else:
            g = Glyph(registrationName="spheres", Input=reader, GlyphType="Sphere")
            g.ScaleArray = ["POINTS", "radius"]
            g.ScaleFactor = 2.0  # the sphere source has radius 0.5
            g.GlyphMode = "All Points"
            g.GlyphType.ThetaResolution = 16
            g.GlyphType.PhiResolution = 12
            if "body" in arrays:
                name, colour = "clump balls", ("body", None)
            else:
                name, colour = "spheres", ("velocity", "Magnitude")
        d = Show(g, view)
        if colour[1]:
            ColorBy(d, ("POINTS", colour[0], colour[1]))
        else:
            ColorBy(d, ("POINTS", colour[0]))
        d.RescaleTransferFunctionToDataRange(True, False)
        d.SetScalarBarVisibility(view, True)
        if colour[0] == "body":
            lut = GetColorTransferFunction("body")
            lut.ApplyPreset("Rainbow Uniform", True)
        Hide(reader, view)
        shown[name] = g
    w = _path("walls.pvd")
    if w:
        walls = PVDReader(registrationName="walls.pvd", FileName=w)
        d = Show(walls, view)
        d.Representation = "Surface"
        d.Opacity = 0.35
        d.ColorArrayName = ["POINTS", ""]
        d.AmbientColor = [0.75, 0.75, 0.8]
        d.DiffuseColor = [0.75, 0.75, 0.8]
        shown["walls"] = walls
    f = _path("solid_fraction.pvd")
    if f:
        field = PVDReader(registrationName="solid_fraction.pvd", FileName=f)
        arrays = list(field.PointData.keys()) + list(field.CellData.keys())
        d = Show(field, view)
        d.Representation = "Volume"
        if arrays:
            assoc = "POINTS" if arrays[0] in field.PointData.keys() else "CELLS"
            ColorBy(d, (assoc, arrays[0]))
            d.RescaleTransferFunctionToDataRange(True, False)
        shown["solid fraction"] = field
    scene = GetAnimationScene()
    scene.UpdateAnimationUsingDataTimeSteps()
    return shown


def _bounds(proxy):
    proxy.UpdatePipeline(GetAnimationScene().AnimationTime)
    return list(proxy.GetDataInformation().GetBounds())


def main(argv):
    view = GetActiveViewOrCreate("RenderView")
    shown = show_run(view)
    scene = GetAnimationScene()
    times = GetTimeKeeper().TimestepValues
    times = list(times) if hasattr(times, "__len__") else [times]
    t = times[-1] if times else 0.0
    if "--time" in argv:
        t = float(argv[argv.index("--time") + 1])
    scene.AnimationTime = t
    view.ViewTime = t
    view.CameraPosition = [1, -1.6, 0.9]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    grains_shown = [v for k, v in shown.items() if k in ("spheres", "ellipsoids", "clump balls")]
    if grains_shown:  # frame the grains (plane walls are drawn larger than the box)
        b = _bounds(grains_shown[0])
        if b[0] <= b[1]:
            view.ResetCamera(*b)
        d = GetDisplayProperties(grains_shown[0], view)
        d.RescaleTransferFunctionToDataRange(False, True)
    if "--bounds" in argv:
        print(json.dumps({"time": t, "shown": {k: _bounds(v) for k, v in shown.items()}}))
    if "--screenshot" in argv:
        size = [1200, 900]
        if "--size" in argv:
            size = [int(x) for x in argv[argv.index("--size") + 1].split("x")]
        SaveScreenshot(argv[argv.index("--screenshot") + 1], view, ImageResolution=size)
    elif "--bounds" not in argv:
        Render(view)


main(sys.argv)
)PV";
}

void write_paraview_state(const std::filesystem::path& out_dir) {
  const auto file = out_dir / "view.py";
  const auto tmp = out_dir / ".view.py.tmp";
  {
    std::ofstream o(tmp);
    o << paraview_state_script();
    o.flush();
    if (!o) throw std::runtime_error("could not write '" + tmp.string() + "'");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) throw std::runtime_error("could not write '" + file.string() + "': " + ec.message());
}

}  // namespace grains::io
