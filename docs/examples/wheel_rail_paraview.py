"""The tutorial's elastic wheel on the rail (docs/tutorial.md, "An elastic wheel on a rail"), as
pvpython does it: the last pass's loaded state, the rail and the wheel's disc (roller.pvd's VTU
files) each warped by its displacement (at scale 1: the rail's surface has flowed 1.3 mm along the
track in ten passes, which a larger scale would shift away from the wheel), both coloured by von
Mises; a PNG of the contact.

usage: xvfb-run -a pvpython docs/examples/wheel_rail_paraview.py out/wheel_rail_r260 docs/img/wheel_rail_paraview.png
"""
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetColorTransferFunction, Render, SaveScreenshot,
                             Show, WarpByVector, XMLUnstructuredGridReader)

out, png = sys.argv[1], sys.argv[2]
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1000, 560]
view.OrientationAxesVisibility = 0
mises = GetColorTransferFunction("von_mises")
for name in ("step_0010_loaded.vtu", "roller_0010_loaded.vtu"):  # the rail, then the wheel
    warp = WarpByVector(Input=XMLUnstructuredGridReader(FileName=[out + "/" + name]))
    warp.Vectors = ["POINTS", "displacement"]
    shown = Show(warp, view)
    ColorBy(shown, ("CELLS", "von_mises"))
    shown.LookupTable = mises
mises.RescaleTransferFunction(0.0, 1000.0)
shown.SetScalarBarVisibility(view, True)
Render(view)
view.CameraPosition = [411.8, 412.0, 200.0]  # the contact: the wheel's centre x, the rail's top
view.CameraFocalPoint = [411.8, 412.0, 0.0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 20.0
Render(view)
SaveScreenshot(png, view, ImageResolution=[1000, 560])
print("rendered the loaded state of %s into %s" % (out, png))
