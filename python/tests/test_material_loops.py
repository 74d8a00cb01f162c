"""material-loops on the shipped R260 scene: the uniaxial path of roller's return mapping converges
to the monotonic closed form at first order in the step (the closed form of the command's dashed
curve), the stress-controlled cycle reaches its turning stresses and ratchets less every cycle, and
the command writes its two files into the folder it is given."""
import csv
import os
import tomllib

import numpy as np

from rollerpy import inprocess
from rollerpy.paths import PROBLEMS
from rollerpy.plots import material_loops

SCENE = os.path.join(PROBLEMS, "ratchet_rail.toml")


def test_the_first_loading_converges_to_the_closed_form_at_first_order():
    scene = inprocess.load_scene(SCENE)
    material = tomllib.loads(scene.toml())["material"]
    assert len(material["chaboche_C"]) == 6 and material["voce_Q"] == -40.0
    errors = []
    for steps in (200, 400, 800):
        path = inprocess._roller.uniaxial_path(scene, "strain", [0.01], steps)
        errors.append(path["stress"][-1] - material_loops.monotonic_stress(material, path["eq_plastic_strain"][-1]))
    # Backward Euler's error halves with the step, and the extrapolated value is the closed form's.
    assert abs(errors[0] / errors[1] - 2.0) < 0.05 and abs(errors[1] / errors[2] - 2.0) < 0.05
    extrapolated = 2.0 * errors[2] - errors[1]
    assert abs(extrapolated) < 1e-3 * abs(errors[2]) + 1e-6 * path["stress"][-1]


def test_the_stress_cycle_reaches_its_turning_points_and_ratchets_less_each_cycle():
    scene = inprocess.load_scene(SCENE)
    path = inprocess._roller.uniaxial_path(scene, "stress", [550.0, -350.0] * 4, 20)
    assert np.allclose(path["stress"][20::40], 550.0, rtol=1e-10)
    assert np.allclose(path["stress"][40::40], -350.0, rtol=1e-10)
    per_cycle = np.diff(path["strain"][20::40])
    assert np.all(per_cycle > 0.0) and np.all(np.diff(per_cycle) < 0.0)


def test_the_command_writes_its_csv_and_figure(tmp_path):
    out = str(tmp_path / "loops")
    assert material_loops.main([SCENE, "--out", out, "--amplitudes", "0.005", "--cycles", "2"]) == 0
    with open(os.path.join(out, material_loops.CSV), newline="") as f:
        rows = list(csv.DictReader(f))
    strain_rows = [r for r in rows if r["control"] == "strain"]
    assert len(strain_rows) == 2 * 2 * material_loops.STEPS_PER_BRANCH + material_loops.STEPS_PER_BRANCH + 1
    assert abs(max(float(r["strain"]) for r in strain_rows) - 0.005) < 1e-12
    assert os.path.getsize(os.path.join(out, material_loops.PNG)) > 10000
