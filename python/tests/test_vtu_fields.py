"""The VTU files of a run hold what its tables hold: the contact point data (contact_pressure,
contact_traction, contact_status) equal contact.csv at every candidate node and are zero
elsewhere, and with small kinematics the strain of a step (strain_increment) is the difference of
the total strains of consecutive steps (docs/scenes.md, Outputs)."""
import os

import numpy as np
import pytest

from rollerpy.outputs import read_contact, read_numbers
from rollerpy.paths import PROBLEMS
from rollerpy.runner import roller_command, run
from rollerpy.vtu import read_vtu, vtu_path

STATUS = {"open": 0, "stick": 1, "slip": 2}


def test_contact_point_data_equal_contact_csv(cattaneo_out):
    rows = read_contact(cattaneo_out)
    seen = set()
    for step in sorted({int(r["step"]) for r in rows}):
        point = read_vtu(vtu_path(cattaneo_out, step)).point_data
        at_step = [r for r in rows if int(r["step"]) == step]
        nodes = [int(r["node"]) - 1 for r in at_step]  # thesis numbers are 1-based
        for r, a in zip(at_step, nodes):
            assert point["contact_pressure"][a] == pytest.approx(float(r["p_n"]), abs=1e-9 * (1 + abs(float(r["p_n"]))))
            assert point["contact_traction"][a] == pytest.approx(float(r["p_t"]), abs=1e-9 * (1 + abs(float(r["p_t"]))))
            assert point["contact_status"][a] == STATUS[r["status"]]
            seen.add(r["status"])
        others = np.setdiff1d(np.arange(len(point["contact_pressure"])), nodes)
        for name in ("contact_pressure", "contact_traction", "contact_status"):
            assert np.all(point[name][others] == 0.0), name
    assert seen == {"open", "stick", "slip"}  # every status was compared


def test_step_strain_is_the_difference_of_the_totals(cattaneo_out):
    steps = sorted({int(r["step"]) for r in read_contact(cattaneo_out)})
    first = read_vtu(vtu_path(cattaneo_out, 0)).cell_data
    assert np.all(first["strain_increment"] == 0.0)
    previous = first["strain"]
    for step in steps:
        cells = read_vtu(vtu_path(cattaneo_out, step)).cell_data
        scale = np.abs(cells["strain"]).max()
        assert np.abs(cells["strain_increment"]).max() > 1e-3 * scale
        np.testing.assert_allclose(cells["strain_increment"], cells["strain"] - previous, atol=1e-12 * scale)
        previous = cells["strain"]


def test_fatigue_cell_fields_lay_fatigue_csv_along_the_track_window(roller, tmp_path):
    """A plastic three-pass run with [fatigue]: each pass's last VTU holds dang_van_index and
    fi_sub_index, in every element of passes.csv's track window the row of fatigue.csv nearest its
    depth, and 0 outside the window."""
    out = str(tmp_path / "fatigue")
    options = ["--set", "material.yield_stress=600.0", "--set", "material.tangent_modulus=2100.0",
               "--set", "steps.count=8", "--set", "passes.count=3",
               "--set", "roller.path=[{steps=[1,2], dy=-0.05}, {steps=[3,6], dx=2.0, slip=0.002}, "
               "{steps=[7,8], dy=0.3}]",
               "--set", "fatigue.dang_van_a=0.3", "--set", "fatigue.dang_van_limit=300.0",
               "--set", "fatigue.shear_fatigue_limit=300.0", "--set", "fatigue.critical_shear_strain=11.0"]
    run(roller_command(roller, os.path.join(PROBLEMS, "rolling_friction.toml"), out, *options),
        out + ".log").check()
    passes = read_numbers(os.path.join(out, "passes.csv"))
    fatigue = read_numbers(os.path.join(out, "fatigue.csv"))
    checked = 0
    for p in passes:
        vtu = read_vtu(vtu_path(out, int(p["step"])))
        rows = [r for r in fatigue if int(r["pass"]) == int(p["pass"])]
        depths = np.array([r["depth"] for r in rows])
        top = vtu.reference[:, 1].max()
        for e, nodes in enumerate(vtu.elements):
            centre = vtu.reference[nodes].mean(axis=0)
            if p["track_start"] <= centre[0] <= p["track_end"]:
                row = rows[int(np.argmin(np.abs(depths - (top - centre[1]))))]
                assert vtu.cell_data["dang_van_index"][e] == pytest.approx(row["dang_van_index"], rel=1e-12)
                assert vtu.cell_data["fi_sub_index"][e] == pytest.approx(row["fi_sub_index"], rel=1e-12)
                checked += 1
            else:
                assert vtu.cell_data["dang_van_index"][e] == 0.0 and vtu.cell_data["fi_sub_index"][e] == 0.0
        assert np.max(vtu.cell_data["dang_van_index"]) > 0.0
    assert checked >= 3 * 30  # the window's columns over the strip's 30 rows, every pass
