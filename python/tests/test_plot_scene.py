#!/usr/bin/python3
"""scripts/plot_scene.py on a small output folder (Cattaneo at its default mesh): every figure it
names is written as a PNG, with the options of docs/figures.md (zoom window, element values,
explicit levels, overlays), and bad options stop with a message naming them.

usage: /usr/bin/python3 tests/scripts/test_plot_scene.py ROLLER_EXE   (CTest passes build/roller)
"""
import os
import subprocess
import sys
import unittest

from scene_run import run_scene

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PLOT = [sys.executable, os.path.join(ROOT, "scripts", "plot_scene.py")]
ROLLER = None


def is_png(path):
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 1000


class PlotScene(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = run_scene(ROLLER, "cattaneo")
        cls.figs = os.path.join(cls.out, "figures")

    def plot(self, *args):
        return subprocess.run(PLOT + [self.out] + list(args), capture_output=True, text=True)

    def test_the_named_figures_are_written(self):
        r = self.plot("--steps", "2,8", "--pairs", "4/8", "--levels", "100", "--mesh-steps", "8",
                      "--pressure-steps", "1-8", "--mesh-pairs", "4/8", "--mark-nodes", "5,101",
                      "--compare", self.out, "--compare-steps", "8")
        self.assertEqual(r.returncode, 0, r.stderr)
        names = ["map_%s_step%d.png" % (f, s) for s in (2, 8)
                 for f in ("sqrt_I2", "tau_xx", "tau_yy", "tau_xy", "eps_xx", "eps_yy", "eps_xy",
                           "deps_xx", "deps_yy", "deps_xy", "u_y")]
        names += ["overlay_%s_steps4-8.png" % f for f in ("sqrt_I2", "tau_xx", "tau_yy", "tau_xy")]
        names += ["compare_%s_step8.png" % f for f in ("sqrt_I2", "tau_xx", "tau_yy", "tau_xy")]
        names += ["pressure.png", "profile.png", "mesh_step8.png", "mesh_steps4-8.png", "compare_pressure.png"]
        for name in names:
            self.assertTrue(is_png(os.path.join(self.figs, name)), name)

    def test_zoom_element_values_and_level_lists(self):
        for args in (["--values", "element", "--fields", "tau_xy"], ["--xlim", "90,110", "--ylim", "80,100"],
                     ["--whole", "--levels=-300,-100,100,300", "--fields", "tau_xx"]):
            path = os.path.join(self.figs, "map_%s_step8.png" % (args[-1] if "--fields" in args else "sqrt_I2"))
            if os.path.exists(path):
                os.remove(path)
            r = self.plot("--steps", "8", *args)
            self.assertEqual(r.returncode, 0, "%s: %s" % (args, r.stderr))
            self.assertTrue(is_png(path), args)

    def test_bad_options_are_named(self):
        for args, expected in ((["--levels", "0"], "--levels 0: a spacing must be positive"),
                               (["--xlim", "5,1"], "--xlim 5,1: expected LOW,HIGH"),
                               (["--ylim", "1"], "--ylim 1: expected 2 numbers"),
                               (["--levels", "a,b"], "--levels a,b: expected numbers"),
                               (["--mesh-pairs", "4/99"], "--mesh-pairs: groups of 2 to 4 steps")):
            r = self.plot(*args)
            self.assertNotEqual(r.returncode, 0, args)
            self.assertIn(expected, r.stderr)


if __name__ == "__main__":
    ROLLER = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
