"""stationary-check's measure of a pass from the field files: over passes.csv's own window it
gives passes.csv's numbers (roller's C++ measure_pass), for a transient run and for a stationary
one, and a stationary run's residual strip, a long track's, gives the same numbers on any stretch
of it, its total shear is its plastic shear and its sigma_xx the long track's of its plastic
strain."""
import os

import numpy as np
import pytest

from rollerpy.outputs import read_numbers, read_rows
from rollerpy.runner import roller_command, run, set_options
from rollerpy.validation.make_shakedown_scenes import A, write_scenes
from rollerpy.validation.stationary_check import (SXX_DEPTHS, elastic_constants, endless_ring, link_transients,
                                                  long_track_sxx, measure, middle_windows, pass_fields,
                                                  plastic_shear, stretch_metrics, sxx_table)


@pytest.fixture(scope="module")
def runs(roller, tmp_path_factory):
    """The shakedown strip at p0/k = 4.5 on 0.5 mm elements, 2 passes of a 6a track in steps of a,
    with both methods (a few seconds each)."""
    folder = str(tmp_path_factory.mktemp("stationary_check"))
    scene, = write_scenes([4.5], 2, 0.5, folder, track=6.0, step=1.0)
    outs = {}
    for method, pairs in (("transient", []), ("stationary", [("passes.method", '"stationary"'),
                                                             ("output.every", "1")])):
        out = os.path.join(folder, method)
        run(roller_command(roller, scene, out, *set_options(pairs)), out + ".log").check()
        outs[method] = out
    outs["elastic"] = elastic_constants(scene)
    return outs


@pytest.mark.parametrize("method", ["transient", "stationary"])
def test_the_window_of_passes_csv_gives_its_numbers(runs, method):
    rows = read_numbers(os.path.join(runs[method], "passes.csv"))
    fields = pass_fields(runs[method], 2)
    for k, row in enumerate(rows):
        m = stretch_metrics(fields[k + 1], fields[k], row["track_start"], row["track_end"], A, runs["elastic"])
        assert m["mean"] > 1e-4  # the pass yields
        assert m["mean"] == pytest.approx(row["mean_plastic_increment"], rel=1e-9)
        assert m["band"] == pytest.approx(row["band_plastic_increment"], rel=1e-9)
        assert m["net_shear"] == pytest.approx(row["residual_shear_increment"], rel=1e-9, abs=1e-15)


def test_a_stationary_residual_strip_is_the_same_on_every_stretch(runs):
    fields = pass_fields(runs["stationary"], 2)
    for k in range(2):
        near = stretch_metrics(fields[k + 1], fields[k], 40.0, 48.0, A, runs["elastic"])
        far = stretch_metrics(fields[k + 1], fields[k], 60.0, 68.0, A, runs["elastic"])
        assert near["mean"] > 1e-4
        assert near["mean"] == pytest.approx(far["mean"], rel=1e-6)
        assert near["integral"] == pytest.approx(far["integral"], rel=1e-6)
        assert near["sxx"][:, 1] == pytest.approx(far["sxx"][:, 1], rel=1e-6, abs=1e-6)
        # The displacement is the long track's too: the net shear is the same everywhere, and it is
        # the plastic shear (no sigma_xy), as the residual sigma_xx is the long track's of its
        # plastic strain.
        assert abs(near["net_shear"]) > 1e-5
        assert near["net_shear"] == pytest.approx(far["net_shear"], rel=1e-6)
        assert near["net_plastic_shear"] == pytest.approx(near["net_shear"], rel=1e-9)
        assert near["sxx_long"][:, 1] == pytest.approx(near["sxx"][:, 1], rel=1e-6, abs=1e-6)
        # and its surface moves alike everywhere, by passes.csv's surface_dux
        row = read_numbers(os.path.join(runs["stationary"], "passes.csv"))[k]
        assert near["surface_dux"] == pytest.approx(far["surface_dux"], rel=1e-9)
        assert near["surface_dux"] == pytest.approx(row["surface_dux"], rel=1e-9)
    assert plastic_shear(fields[2], runs["elastic"]) == pytest.approx(2.0 * fields[2].cell_data["strain"][:, 3],
                                                                      rel=1e-9, abs=1e-15)


def test_the_middle_stretch_and_the_residual_table(runs):
    """The transient read on 3a either side of its track's middle (the 6a track from x = 92), and the
    table of the residual sigma_xx at SXX_DEPTHS: the rows nearest to them, every pass."""
    fields = pass_fields(runs["transient"], 2)
    middle = measure(fields, middle_windows(2, A, 6.0, 92.0), A, runs["elastic"])
    for k in range(2):
        direct = stretch_metrics(fields[k + 1], fields[k], 92.0, 92.0 + 6.0 * A, A, runs["elastic"])
        assert middle[k]["mean"] == pytest.approx(direct["mean"], rel=1e-12)
    profile = middle[0]["sxx"]
    text = sxx_table([("transient", middle, "sxx")], 2, A)
    assert text.count("| transient |") == 2
    for d in SXX_DEPTHS:
        row = int(np.argmin(np.abs(profile[:, 0] - d * A)))
        assert abs(profile[row, 0] - d * A) <= 0.5 * (profile[1, 0] - profile[0, 0]) + 1e-9  # the nearest row
        assert ("%.2f" % profile[row, 0]) in text.splitlines()[3]
        assert ("%.0f" % profile[row, 1]) in text.splitlines()[5]


def test_the_long_track_stress_of_a_plastic_strain():
    """long_track_sxx reads the plastic strain from the stress and the total strain of a finite
    strip and gives the closed form of a long track's: -E (ep_xx + nu ep_zz) / (1 - nu^2)."""
    young, nu = 210000.0, 0.3
    lam, g = young * nu / ((1 + nu) * (1 - 2 * nu)), young / (2 * (1 + nu))
    plastic = np.array([[1.3e-3, -0.4e-3, -0.9e-3, 0.7e-3], [-2e-4, 5e-4, -3e-4, 0.0]])
    total = np.array([[2.1e-4, -0.6e-3, 0.0, 0.95e-3], [-1e-4, 3e-4, 0.0, 1e-4]])
    elastic = total - plastic
    stress = 2 * g * elastic
    stress[:, :3] += lam * elastic[:, :3].sum(axis=1)[:, None]

    class Fields:
        cell_data = {"stress": np.c_[stress, np.zeros((2, 2))], "strain": np.c_[total, np.zeros((2, 2))]}
    expected = -young * (plastic[:, 0] + nu * plastic[:, 2]) / (1 - nu * nu)
    assert long_track_sxx(Fields, (young, nu)) == pytest.approx(expected, rel=1e-12)


def test_the_stationary_runs_alone(roller, tmp_path, monkeypatch):
    """--steps none: the stationary runs without a transient, the table against the first of them."""
    from rollerpy.validation.stationary_check import main
    monkeypatch.chdir(os.getcwd())  # main moves to the repository's root: back after the test
    out = str(tmp_path / "alone")
    assert main(["--element-size", "0.5", "--track", "20", "--steps", "none", "--phases", "0",
                 "--roller", roller, "--out", out]) == 0
    text = open(os.path.join(out, "stationary_check.md")).read()
    assert "the reference: the stationary, roller, centre +0h" in text
    assert "transient" not in text
    assert "| stationary, roller, centre +0h | 1 |" in text and "| +0.0 % |" in text
    assert "| stationary, Hertz load | 2 |" in text
    assert os.path.getsize(os.path.join(out, "stationary_check.png")) > 10000


def test_a_periodic_transient_is_read_across_its_seam(roller, tmp_path):
    """A periodic strip (make-shakedown-scenes --periodic: one period, the 6a track, 0.5 mm
    elements): the roller presses in its middle and rolls the whole period over the seam; passes.csv's
    window, the half opposite the press, crosses the seam, and stretch_metrics with the period reads
    it as roller's C++ measure_pass does."""
    scene, = write_scenes([4.5], 2, 0.5, str(tmp_path), track=6.0, step=1.0, periodic=True)
    text = open(scene).read()
    assert "periodic = true" in text and "length = 12.0" in text and "centre = [6.0, 200.0]" in text
    out = str(tmp_path / "periodic")
    run(roller_command(roller, scene, out), out + ".log").check()
    rows = read_numbers(os.path.join(out, "passes.csv"))
    fields = pass_fields(out, 2)
    elastic = elastic_constants(scene)
    for k, row in enumerate(rows):
        assert row["track_start"] < 12.0 < row["track_end"]  # across the seam
        m = stretch_metrics(fields[k + 1], fields[k], row["track_start"], row["track_end"], A, elastic, period=12.0)
        assert m["mean"] > 1e-4
        assert m["mean"] == pytest.approx(row["mean_plastic_increment"], rel=1e-9)
        assert m["band"] == pytest.approx(row["band_plastic_increment"], rel=1e-9)
        assert m["net_shear"] == pytest.approx(row["residual_shear_increment"], rel=1e-9, abs=1e-15)
        assert abs(m["surface_dux"]) > 1e-5
        unwrapped = stretch_metrics(fields[k + 1], fields[k], row["track_start"], row["track_end"], A, elastic)
        assert unwrapped["mean"] != pytest.approx(m["mean"], rel=1e-3)


def test_a_ring_rolled_on_is_measured_opposite_the_roller(roller, tmp_path):
    """A ring pressed once and rolled on (make-shakedown-scenes --continuous: 2 periods of the 6a
    track in steps of a, 0.5 mm elements): fields every period with the roller 3 steps before where
    it pressed, half a period from continuous_windows' middle. An elastic ring is then in the same
    state at every period's end, so the differences over a period hold nothing of the roller's
    elastic field, which the stress as read does; a plastic ring yields in the window every period."""
    from rollerpy.validation.stationary_check import continuous_windows
    scene, = write_scenes([4.5], 2, 0.5, str(tmp_path), track=6.0, step=1.0, periodic=True, continuous=True)
    text = open(scene).read()
    assert "[passes]" not in text and "count = 12 " in text and "every = 6 " in text and "dx = 18.0" in text
    windows = continuous_windows(2, A, 6.0, 6.0, 1.0)
    elastic = elastic_constants(scene)
    metrics = {}
    for name, pairs in (("elastic", [("material.yield_stress", "1e7")]), ("plastic", [])):
        out = str(tmp_path / name)
        run(roller_command(roller, scene, out, *set_options(pairs)), out + ".log").check()
        xs = {int(r["step"]): float(r["xc"]) for r in read_rows(os.path.join(out, "roller.csv"))}
        for k, (x0, x1) in enumerate(windows):
            # The roller half a period from the window's middle (mod 12 mm), 3 steps (6 mm) short of the press.
            assert (xs[6 * (k + 1)] - 0.5 * (x0 + x1)) % 12.0 == pytest.approx(6.0, abs=1e-9)
        metrics[name] = measure(pass_fields(out, 2), windows, A, elastic, period=12.0)
    # The first period starts before the press, without the roller's field: its shear and u_x, odd
    # about the roller, cancel over the window symmetric about the point opposite it (not exactly:
    # the roller stands 3a from it here). The second starts and ends with the roller at one place.
    for m, bound in zip(metrics["elastic"], (1e-7, 1e-12)):
        assert abs(m["mean"]) < 1e-12 and abs(m["net_shear"]) < bound and abs(m["surface_dux"]) < bound
        assert np.max(np.abs(m["sxx"][:, 1])) > 1.0      # the roller's elastic field, 3a from the window
        assert np.max(np.abs(m["sxx_long"][:, 1])) < 1e-6  # no plastic strain
    for m in metrics["plastic"]:
        assert m["mean"] > 1e-4


def test_transients_from_an_earlier_check_are_linked_not_run(tmp_path):
    """--transients-from: the transient runs of the steps asked for are linked into the new folder
    (what it holds already stays; scenes and stationary runs are not linked); a step the earlier
    check did not run is an error naming the steps it did."""
    source = tmp_path / "earlier"
    for name in ("scenes", "scenes_s0.1", "transient_s0.1", "transient_s0.05", "transient_s0.2",
                 "stationary_roller_ph0"):
        (source / name).mkdir(parents=True)
        (source / name / "summary.json").write_text(name)
    (source / "transient_s0.3.log").write_text("log")
    out = tmp_path / "new"
    (out / "transient_s0.2").mkdir(parents=True)
    link_transients(str(source), str(out), [0.1, 0.2])
    assert os.path.islink(out / "transient_s0.1")
    assert (out / "transient_s0.1" / "summary.json").read_text() == "transient_s0.1"
    assert not os.path.islink(out / "transient_s0.2")  # held already
    for name in ("scenes", "scenes_s0.1", "stationary_roller_ph0", "transient_s0.05"):
        assert not os.path.exists(out / name)
    with pytest.raises(SystemExit, match=r"holds no transient_s0.3 \(its steps: 0.05, 0.1, 0.2\)"):
        link_transients(str(source), str(out), [0.3])


def test_the_endless_ring_is_the_common_limit_of_two_rings_profiles():
    """Profiles that close in on a limit X geometrically as the ring doubles (as read from above, a
    long track's from below, each by the ratio r of its depth) give X back; where the two rings'
    profiles do not close in, the longer ring's mean."""
    depth = np.array([0.5, 1.0, 1.5, 2.0])
    limit, ratio = np.array([-300.0, -650.0, -500.0, -350.0]), np.array([0.25, 0.3, 0.28, 0.95])
    above, below = np.array([-120.0, -150.0, -110.0, -40.0]), np.array([80.0, 60.0, 70.0, 30.0])

    def ring(k):
        shrink = ratio ** k
        return {"mean": 1.0 + k, "sxx": np.column_stack([depth, limit + above * shrink]),
                "sxx_long": np.column_stack([depth, limit + below * shrink])}

    shorter, longer = ring(0), ring(1)
    endless, = endless_ring([shorter], [longer])
    assert np.allclose(endless["sxx"][:3, 1], limit[:3], atol=1e-9)
    assert np.allclose(endless["sxx_long"][:3, 1], limit[:3], atol=1e-9)
    assert endless["sxx"][3, 1] == pytest.approx(0.5 * (longer["sxx"][3, 1] + longer["sxx_long"][3, 1]))
    assert endless["mean"] == longer["mean"]
    assert np.array_equal(endless["sxx"][:, 0], depth)


def test_options_it_cannot_take_stop_before_any_run(capsys):
    from rollerpy.validation.stationary_check import main
    for argv, words in ((["--passes", "1"], "give at least 2"), (["--continuous"], "give --periodic too")):
        with pytest.raises(SystemExit) as stop:
            main(argv)
        assert words in str(stop.value)
    with pytest.raises(SystemExit, match="do not fill the 6 mm band"):
        write_scenes([4.5], 2, 0.8, "/nonexistent", track=6.0, step=1.0)  # 6 mm is not a whole number of 0.8
