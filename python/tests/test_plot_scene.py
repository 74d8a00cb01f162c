"""`rollerpy plot-scene` and `rollerpy plot-forces` on small output folders (Cattaneo at its
default mesh, Hertz): every figure they name is written as a PNG, with the options of
docs/figures.md (zoom window, element values, explicit levels, overlays, the Hertz step); maps of
signed fields are diverging and centred at zero, magnitudes sequential, the roller is drawn; bad
options, unknown fields and steps the run does not have stop with a message and a non-zero exit."""
import csv
import os
import subprocess

import pytest
from conftest import LAUNCHER, run_scene

from rollerpy.outputs import read_rows
from rollerpy.plots import plt
from rollerpy.plots.scene import PlotError, hertz_figure, map_figure


def is_png(path):
    with open(path, "rb") as f:
        return f.read(8) == b"\x89PNG\r\n\x1a\n" and os.path.getsize(path) > 1000


def plot(out, *args, command="plot-scene"):
    return subprocess.run([LAUNCHER, command, out] + list(args), capture_output=True, text=True)


@pytest.fixture(scope="module")
def hertz_out(roller, tmp_path_factory):
    return run_scene(roller, "hertz", str(tmp_path_factory.mktemp("scenes")))


def test_the_named_figures_are_written(cattaneo_out):
    r = plot(cattaneo_out, "--steps", "2,8", "--pairs", "4/8", "--levels", "100", "--mesh-steps", "8",
             "--pressure-steps", "1-8", "--mesh-pairs", "4/8", "--mark-nodes", "5,101",
             "--compare", cattaneo_out, "--compare-steps", "8")
    assert r.returncode == 0, r.stderr
    names = ["map_%s_step%d.png" % (f, s) for s in (2, 8)
             for f in ("von_mises", "sqrt_I2", "eq_plastic_strain", "stress_xx", "stress_yy", "stress_xy",
                       "strain_xx", "strain_yy", "strain_xy", "strain_increment_xx", "strain_increment_yy",
                       "strain_increment_xy", "displacement_x", "displacement_y")]
    names += ["overlay_%s_steps4-8.png" % f for f in ("von_mises", "stress_xx", "stress_yy", "stress_xy")]
    names += ["compare_%s_step8.png" % f for f in ("von_mises", "stress_xx", "stress_yy", "stress_xy")]
    names += ["pressure.png", "profile.png", "mesh_step8.png", "mesh_steps4-8.png", "compare_pressure.png",
              "forces.png"]
    for name in names:
        assert is_png(os.path.join(cattaneo_out, "figures", name)), name


@pytest.mark.parametrize("args", [["--values", "element", "--fields", "stress_xy"],
                                  ["--xlim", "90,110", "--ylim", "80,100"],
                                  ["--whole", "--levels=-300,-100,100,300", "--fields", "stress_xx"]])
def test_zoom_element_values_and_level_lists(cattaneo_out, args):
    path = os.path.join(cattaneo_out, "figures",
                        "map_%s_step8.png" % (args[-1] if "--fields" in args else "von_mises"))
    if os.path.exists(path):
        os.remove(path)
    r = plot(cattaneo_out, "--steps", "8", *args)
    assert r.returncode == 0, r.stderr
    assert is_png(path)


def test_signed_fields_diverge_about_zero_and_magnitudes_are_sequential(hertz_out):
    signed = map_figure(hertz_out, 4, "stress_yy")
    assert signed.bands.cmap.name == "RdBu_r"
    assert signed.bands.norm.vmin == pytest.approx(-signed.bands.norm.vmax)  # white is zero
    magnitude = map_figure(hertz_out, 4, "von_mises")
    assert magnitude.bands.cmap.name == "viridis"
    assert magnitude.bands.norm.vmin == 0.0
    # The colour bands change at the contour lines' levels (and at the data's extremes).
    assert len(magnitude.levels) >= 3
    assert list(magnitude.bands.levels[1:-1]) == magnitude.levels
    labels = {t.get_text() for t in magnitude.ax.texts}  # the contour lines' labels, at those levels
    assert labels and labels <= {"%g" % v for v in magnitude.levels}
    plt.close(signed.fig)
    plt.close(magnitude.fig)


def test_maps_zoom_on_the_contact_and_draw_the_roller(hertz_out):
    zoomed, whole = map_figure(hertz_out, 4, "stress_xy"), map_figure(hertz_out, 4, "stress_xy", whole=True)
    x0, x1 = zoomed.ax.get_xlim()
    w0, w1 = whole.ax.get_xlim()
    assert x1 - x0 < 0.5 * (w1 - w0)
    pose = read_rows(os.path.join(hertz_out, "roller.csv"))[-1]
    circles = [p for p in zoomed.ax.patches if isinstance(p, plt.Circle)]
    assert len(circles) == 1
    assert circles[0].center == (float(pose["xc"]), float(pose["yc"]))
    assert x0 < float(pose["xc"]) < x1
    assert "[MPa]" in zoomed.fig.axes[1].get_xlabel()  # the colour bar's unit
    assert zoomed.ax.get_xlabel() == "x [mm]" and zoomed.ax.get_ylabel() == "y [mm]"
    plt.close(zoomed.fig)
    plt.close(whole.fig)


def test_hertz_at_a_chosen_step_and_after_a_lift(hertz_out, tmp_path):
    fig = hertz_figure(hertz_out, 2)
    assert "step 2" in fig.axes[0].get_title()
    plt.close(fig)
    with pytest.raises(PlotError, match="--hertz-step 0: the roller carries no load"):
        hertz_figure(hertz_out, 0)
    # A run that ends with a lift: the default is the last step whose roller carries load.
    lifted = str(tmp_path / "lifted")
    os.makedirs(lifted)
    for name in ("scene.resolved.toml", "contact.csv"):
        os.symlink(os.path.join(hertz_out, name), os.path.join(lifted, name))
    rows = read_rows(os.path.join(hertz_out, "roller.csv"))
    rows.append(dict(rows[-1], step="5", fy="2.3e-05"))  # a lifted roller's round-off force
    with open(os.path.join(lifted, "roller.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    fig = hertz_figure(lifted)
    assert "step 4" in fig.axes[0].get_title()
    plt.close(fig)


def test_forces_figure(hertz_out):
    r = plot(hertz_out, "--label", "Hertz", command="plot-forces")
    assert r.returncode == 0, r.stderr
    assert is_png(os.path.join(hertz_out, "figures", "forces.png"))
    r = plot(os.path.dirname(hertz_out), command="plot-forces")
    assert r.returncode != 0 and "has no roller.csv" in r.stderr


@pytest.mark.parametrize("args, expected", [
    (["--levels", "0"], "--levels 0: a spacing must be positive"),
    (["--xlim", "5,1"], "--xlim 5,1: expected LOW,HIGH"),
    (["--ylim", "1"], "--ylim 1: expected 2 numbers"),
    (["--levels", "a,b"], "--levels a,b: expected numbers"),
    (["--steps", "99"], "--steps 99: the run has no step 99 (it has steps 0-8)"),
    (["--profile-steps", "3-12"], "--profile-steps 3-12: the run has no step 9"),
    (["--hertz-step", "99"], "--hertz-step 99: the roller carries no load at that step; loaded steps: 1-8"),
    (["--fields", "tau_xy"], "--fields tau_xy: unknown field (now stress_xy, the VTU's name)"),
    (["--fields", "stress"], "--fields stress: unknown field; fields: stress_xx"),
    (["--spacing", "sqrt_I3=10"], "--spacing sqrt_I3: unknown field"),
    (["--pairs", "4"], "--pairs 4: groups of 2 to 4 steps"),
    (["--mesh-pairs", "4/99"], "--mesh-pairs 4/99: the run has no step 99")])
def test_bad_options_are_named(cattaneo_out, args, expected):
    r = plot(cattaneo_out, *args)
    assert r.returncode == 1, args
    assert expected in r.stderr
