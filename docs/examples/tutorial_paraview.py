"""The tutorial's ParaView view (docs/tutorial.md, "Look at it in ParaView"), as pvpython does it:
the burnishing run's first loaded state (the roller at mid-track), warped by its displacement at
scale 200, coloured by von Mises, the roller beside it; a PNG of the contact region.

usage: xvfb-run -a pvpython docs/examples/tutorial_paraview.py out/my_burnishing docs/img/tutorial_paraview.png
"""
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, PVDReader, Render, SaveScreenshot,
                             Show, WarpByVector)

out, png = sys.argv[1], sys.argv[2]
strip = PVDReader(FileName=out + "/fields.pvd")
roller = PVDReader(FileName=out + "/roller.pvd")
# The written steps: 0, then per pass its mid-track (loaded) state and its end (lifted).
loaded = list(strip.TimestepValues)[1]
warp = WarpByVector(Input=strip)
warp.Vectors = ["POINTS", "displacement"]
warp.ScaleFactor = 200.0  # the dent is about 3 micrometres deep on a 3 mm strip

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [1000, 420]
view.OrientationAxesVisibility = 0
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = loaded
shown = Show(warp, view)
ColorBy(shown, ("POINTS", "von_mises_nodal"))
shown.RescaleTransferFunctionToDataRange(False, True)
shown.SetScalarBarVisibility(view, True)
Show(roller, view)
Render(view)  # the first render places the camera on everything; then the contact region
view.CameraPosition = [6.0, 2.2, 30.0]
view.CameraFocalPoint = [6.0, 2.2, 0.0]
view.CameraParallelProjection = 1
view.CameraParallelScale = 1.8
Render(view)
SaveScreenshot(png, view, ImageResolution=[1000, 420])
print("rendered step time %g of %s into %s" % (loaded, out, png))
