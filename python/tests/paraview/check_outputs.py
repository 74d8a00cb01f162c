"""Run by pvpython (ParaView's Python; python/tests/test_paraview.py): opens a run's fields.pvd and
roller.pvd as a ParaView user does, warps the strip by its displacement, takes the principal
stresses of the symmetric stress tensor and renders the last step to a PNG. Prints one JSON line
of what it found, for the test to check."""
import json
import sys

import numpy as np
from paraview import servermanager as sm
from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene, PVDReader, PythonCalculator, Render,
                             SaveScreenshot, Show, WarpByVector)
from vtk.numpy_interface import dataset_adapter as dsa

out, png = sys.argv[1], sys.argv[2]
strip = PVDReader(FileName=out + "/fields.pvd")
times = list(strip.TimestepValues)
last = times[-1]
warp = WarpByVector(Input=strip)
warp.Vectors = ["POINTS", "displacement"]
# The principal stresses from the six components in ParaView's order (XX, YY, ZZ, XY, YZ, XZ).
principal = PythonCalculator(Input=warp, ArrayAssociation="Cell Data", ArrayName="principal_max",
                             Expression="0.5*(stress[:,0]+stress[:,1]) + sqrt((0.5*(stress[:,0]-stress[:,1]))**2"
                                        " + stress[:,3]**2)")
principal.UpdatePipeline(last)
data = dsa.WrapDataObject(sm.Fetch(principal))
stress_array = data.VTKObject.GetCellData().GetArray("stress")
names = [stress_array.GetComponentName(c) for c in range(stress_array.GetNumberOfComponents())]
stress = np.asarray(data.CellData["stress"])
# Every element's 3x3 tensor from the six components; its largest eigenvalue in the plane.
full = np.zeros((len(stress), 3, 3))
for (i, j), c in {(0, 0): 0, (1, 1): 1, (2, 2): 2, (0, 1): 3, (1, 2): 4, (0, 2): 5}.items():
    full[:, i, j] = full[:, j, i] = stress[:, c]
in_plane = np.linalg.eigvalsh(full[:, :2, :2])[:, -1]

roller = PVDReader(FileName=out + "/roller.pvd")
roller.UpdatePipeline(last)
circle = dsa.WrapDataObject(sm.Fetch(roller))

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [800, 400]
shown = Show(warp, view)
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = last
ColorBy(shown, ("POINTS", "von_mises_nodal"))
shown.RescaleTransferFunctionToDataRange(False, True)
shown.SetScalarBarVisibility(view, True)
Show(roller, view)
view.ResetCamera()
Render(view)
SaveScreenshot(png, view, ImageResolution=[800, 400])

print(json.dumps({
    "times": times,
    "warped": np.asarray(data.Points)[:, :2].tolist(),
    "field_data": {k: float(np.asarray(data.FieldData[k]).ravel()[0]) for k in data.FieldData.keys()},
    "stress_components": names,
    "principal_paraview": np.asarray(data.CellData["principal_max"]).tolist(),
    "principal_numpy": in_plane.tolist(),
    "roller_points": int(circle.GetNumberOfPoints()),
    "roller_lines": int(circle.VTKObject.GetNumberOfLines()),
}))
