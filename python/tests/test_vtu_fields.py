#!/usr/bin/python3
"""The VTU files of a run hold what its tables hold: the contact point data (contact_pressure,
contact_traction, contact_status) equal contact.csv at every candidate node and are zero
elsewhere, and with small kinematics the strain of a step (strain_increment) is the difference of
the total strains of consecutive steps (docs/scenes.md, Outputs).

usage: /usr/bin/python3 tests/scripts/test_vtu_fields.py ROLLER_EXE   (CTest passes build/roller)
"""
import csv
import os
import sys
import unittest

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from plot_scene import read_vtu  # noqa: E402
from scene_run import run_scene  # noqa: E402

ROLLER = None
STATUS = {"open": 0, "stick": 1, "slip": 2}


class VtuFields(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # Cattaneo: small kinematics, friction (stick and slip nodes), 8 steps.
        cls.out = run_scene(ROLLER, "cattaneo")
        with open(os.path.join(cls.out, "contact.csv"), newline="") as f:
            cls.rows = list(csv.DictReader(f))
        cls.steps = sorted({int(r["step"]) for r in cls.rows})

    def vtu(self, step):
        return read_vtu(os.path.join(self.out, "step_%04d.vtu" % step))

    def test_contact_point_data_equal_contact_csv(self):
        seen = set()
        for step in self.steps:
            _, _, point, _ = self.vtu(step)
            rows = [r for r in self.rows if int(r["step"]) == step]
            nodes = [int(r["node"]) - 1 for r in rows]  # thesis numbers are 1-based
            for r, a in zip(rows, nodes):
                self.assertAlmostEqual(point["contact_pressure"][a], float(r["p_n"]), delta=1e-9 * (1 + abs(float(r["p_n"]))))
                self.assertAlmostEqual(point["contact_traction"][a], float(r["p_t"]), delta=1e-9 * (1 + abs(float(r["p_t"]))))
                self.assertEqual(point["contact_status"][a], STATUS[r["status"]])
                seen.add(r["status"])
            others = np.setdiff1d(np.arange(len(point["contact_pressure"])), nodes)
            for name in ("contact_pressure", "contact_traction", "contact_status"):
                self.assertTrue(np.all(point[name][others] == 0.0), name)
        self.assertEqual(seen, {"open", "stick", "slip"})  # every status was compared

    def test_step_strain_is_the_difference_of_the_totals(self):
        previous = self.vtu(0)[3]["strain"]
        self.assertTrue(np.all(self.vtu(0)[3]["strain_increment"] == 0.0))
        for step in self.steps:
            cells = self.vtu(step)[3]
            scale = np.abs(cells["strain"]).max()
            self.assertGreater(np.abs(cells["strain_increment"]).max(), 1e-3 * scale)
            np.testing.assert_allclose(cells["strain_increment"], cells["strain"] - previous, atol=1e-12 * scale)
            previous = cells["strain"]


if __name__ == "__main__":
    ROLLER = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
