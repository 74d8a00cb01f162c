"""Run by pvpython (python/tests/test_paraview.py): opens an elastic roller's roller.pvd (the disc's
VTU files) as a ParaView user does, warps the disc by its displacement and renders the last step
with the strip. Prints one JSON line of what it found, for the test to check."""
import json
import sys

import numpy as np
from paraview import servermanager as sm
from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, PVDReader, Render, SaveScreenshot,
                             Show, WarpByVector)
from vtk.numpy_interface import dataset_adapter as dsa

out, png = sys.argv[1], sys.argv[2]
roller = PVDReader(FileName=out + "/roller.pvd")
times = list(roller.TimestepValues)
last = times[-1]
warp = WarpByVector(Input=roller)
warp.Vectors = ["POINTS", "displacement"]
warp.UpdatePipeline(last)
disc = dsa.WrapDataObject(sm.Fetch(warp))
strip = WarpByVector(Input=PVDReader(FileName=out + "/fields.pvd"))
strip.Vectors = ["POINTS", "displacement"]

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [800, 400]
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = last
for shown in (Show(warp, view), Show(strip, view)):
    ColorBy(shown, ("CELLS", "von_mises"))
    shown.RescaleTransferFunctionToDataRange(False, True)
view.ResetCamera()
Render(view)
SaveScreenshot(png, view, ImageResolution=[800, 400])

points = np.asarray(disc.Points)[:, :2]
force = np.asarray(disc.PointData["contact_force"])[:, :2]
loaded = np.abs(force[:, 1]) > 0
print(json.dumps({
    "times": times,
    "point_arrays": sorted(disc.PointData.keys()),
    "cell_arrays": sorted(disc.CellData.keys()),
    "force": force.sum(axis=0).tolist(),
    "loaded_points": points[loaded].tolist(),
    "von_mises_max": float(np.max(np.asarray(disc.CellData["von_mises"]))),
}))
