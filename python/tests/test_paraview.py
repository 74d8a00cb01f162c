"""The outputs as a ParaView user sees them (docs/scenes.md, Outputs), checked with the real client:
ParaView's pvpython (Debian's paraview, headless under xvfb-run) opens a Hertz run's fields.pvd
and roller.pvd, warps the strip by `displacement`, takes principal stresses of the six-component
`stress` and renders the last step (python/tests/paraview/check_outputs.py). The warped points must
be the deformed positions roller reports in contact.csv. An elastic roller's disc (roller.pvd's VTU
files) warped by its displacement must touch the strip's contact nodes
(python/tests/paraview/check_roller_disc.py)."""
import json
import os
import subprocess

import numpy as np

from conftest import run_scene
from rollerpy.outputs import read_rows
from rollerpy.paths import PROBLEMS
from rollerpy.runner import roller_command, run

SCRIPT = os.path.join(os.path.dirname(__file__), "paraview", "check_outputs.py")
DISC_SCRIPT = os.path.join(os.path.dirname(__file__), "paraview", "check_roller_disc.py")
# -noreset: pvpython's first connection (its OpenGL probe) closes, and an X server that resets
# when its last client leaves refuses the next one for a moment ("bad X server connection",
# 1 run in 5 here; docs/scenes.md, "Scripting ParaView without a display").
XVFB = ["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24 -noreset"]


def test_paraview_opens_warps_and_renders_a_run(roller, tmp_path):
    out = run_scene(roller, "hertz", str(tmp_path))
    png = str(tmp_path / "hertz.png")
    r = subprocess.run(XVFB + ["pvpython", SCRIPT, out, png], capture_output=True, text=True,
                       timeout=300, cwd=str(tmp_path))
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    found = json.loads(r.stdout.strip().splitlines()[-1])
    assert found["times"] == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert found["field_data"] == {"step": 4.0, "pass": 1.0, "time": 4.0}
    assert found["stress_components"] == ["XX", "YY", "ZZ", "XY", "YZ", "XZ"]
    np.testing.assert_allclose(found["principal_paraview"], found["principal_numpy"], rtol=1e-9, atol=1e-9)
    # Warp By Vector gives the deformed strip: the candidates' positions of contact.csv's last step.
    warped = np.array(found["warped"])
    last = [row for row in read_rows(os.path.join(out, "contact.csv")) if int(row["step"]) == 4]
    assert len(last) > 10
    for row in last:
        node = int(row["node"]) - 1  # thesis numbering from 1
        np.testing.assert_allclose(warped[node], [float(row["x"]), float(row["y"])], rtol=1e-12, atol=1e-9)
    assert found["roller_points"] == 181 and found["roller_lines"] == 2  # circle and radius
    assert os.path.getsize(png) > 5000


def test_paraview_shows_an_elastic_roller_touching_the_strip(roller, tmp_path):
    out = str(tmp_path / "hertz_steel_roller")
    run(roller_command(roller, os.path.join(PROBLEMS, "hertz.toml"), out, "--set", "roller.E=2.1e5", "--set",
                       "roller.nu=0.3"), out + ".log").check()
    png = str(tmp_path / "disc.png")
    r = subprocess.run(XVFB + ["pvpython", DISC_SCRIPT, out, png], capture_output=True, text=True, timeout=300,
                       cwd=str(tmp_path))
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    found = json.loads(r.stdout.strip().splitlines()[-1])
    assert found["times"] == [0.0, 1.0, 2.0, 3.0, 4.0]
    assert found["point_arrays"] == ["contact_force", "displacement"]
    assert found["cell_arrays"] == ["stress", "von_mises"]
    # The disc carries the strip's force on the roller (roller.csv's last row).
    fy = float(read_rows(os.path.join(out, "roller.csv"))[-1]["fy"])
    np.testing.assert_allclose(found["force"], [0.0, fy], rtol=1e-9, atol=1e-6 * fy)
    # Warped by its displacement the rim passes through the strip's contact nodes: within 2e-4 mm
    # of a flattening of 0.052 mm (the rim drawn as chords between its nodes, sag h^2/8R' ~ 3e-5
    # mm; the disc loaded by the step's forces, the contact's rim sampled at its start). Measured:
    # 1.0e-4 mm at most.
    rim = np.array(found["loaded_points"])
    rim = rim[np.argsort(rim[:, 0])]
    touching = [row for row in read_rows(os.path.join(out, "contact.csv"))
                if int(row["step"]) == 4 and row["status"] != "open"]
    assert len(touching) > 10
    for row in touching:
        x, y = float(row["x"]), float(row["y"])
        assert abs(y - np.interp(x, rim[:, 0], rim[:, 1])) < 2e-4
    assert os.path.getsize(png) > 5000
