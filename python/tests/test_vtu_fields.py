"""The VTU files of a run hold what its tables hold: the contact point data (contact_pressure,
contact_traction, contact_status) equal contact.csv at every candidate node and are zero
elsewhere, and with small kinematics the strain of a step (strain_increment) is the difference of
the total strains of consecutive steps (docs/scenes.md, Outputs)."""
import numpy as np
import pytest

from rollerpy.outputs import read_contact
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
