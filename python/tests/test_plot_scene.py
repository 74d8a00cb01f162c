"""`rollerpy plot-scene` on a small output folder (Cattaneo at its default mesh): every figure it
names is written as a PNG, with the options of docs/figures.md (zoom window, element values,
explicit levels, overlays), and bad options stop with a message naming them."""
import os
import subprocess

import pytest
from conftest import LAUNCHER


def is_png(path):
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 1000


def plot(out, *args):
    return subprocess.run([LAUNCHER, "plot-scene", out] + list(args), capture_output=True, text=True)


def test_the_named_figures_are_written(cattaneo_out):
    r = plot(cattaneo_out, "--steps", "2,8", "--pairs", "4/8", "--levels", "100", "--mesh-steps", "8",
             "--pressure-steps", "1-8", "--mesh-pairs", "4/8", "--mark-nodes", "5,101",
             "--compare", cattaneo_out, "--compare-steps", "8")
    assert r.returncode == 0, r.stderr
    names = ["map_%s_step%d.png" % (f, s) for s in (2, 8)
             for f in ("sqrt_I2", "tau_xx", "tau_yy", "tau_xy", "eps_xx", "eps_yy", "eps_xy",
                       "deps_xx", "deps_yy", "deps_xy", "u_y")]
    names += ["overlay_%s_steps4-8.png" % f for f in ("sqrt_I2", "tau_xx", "tau_yy", "tau_xy")]
    names += ["compare_%s_step8.png" % f for f in ("sqrt_I2", "tau_xx", "tau_yy", "tau_xy")]
    names += ["pressure.png", "profile.png", "mesh_step8.png", "mesh_steps4-8.png", "compare_pressure.png"]
    for name in names:
        assert is_png(os.path.join(cattaneo_out, "figures", name)), name


@pytest.mark.parametrize("args", [["--values", "element", "--fields", "tau_xy"],
                                  ["--xlim", "90,110", "--ylim", "80,100"],
                                  ["--whole", "--levels=-300,-100,100,300", "--fields", "tau_xx"]])
def test_zoom_element_values_and_level_lists(cattaneo_out, args):
    path = os.path.join(cattaneo_out, "figures", "map_%s_step8.png" % (args[-1] if "--fields" in args else "sqrt_I2"))
    if os.path.exists(path):
        os.remove(path)
    r = plot(cattaneo_out, "--steps", "8", *args)
    assert r.returncode == 0, r.stderr
    assert is_png(path)


@pytest.mark.parametrize("args, expected", [
    (["--levels", "0"], "--levels 0: a spacing must be positive"),
    (["--xlim", "5,1"], "--xlim 5,1: expected LOW,HIGH"),
    (["--ylim", "1"], "--ylim 1: expected 2 numbers"),
    (["--levels", "a,b"], "--levels a,b: expected numbers"),
    (["--mesh-pairs", "4/99"], "--mesh-pairs: groups of 2 to 4 steps")])
def test_bad_options_are_named(cattaneo_out, args, expected):
    r = plot(cattaneo_out, *args)
    assert r.returncode != 0, args
    assert expected in r.stderr
