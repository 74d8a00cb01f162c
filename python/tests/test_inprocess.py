"""roller in the Python process (rollerpy.run over the native module): the in-memory results equal
the files the same run writes, a scene from a dict equals its file, overrides reach path segments,
the progress callback sees every step, and Ctrl-C stops cleanly with the results so far."""
import os
import signal
import subprocess
import sys
import tomllib

import numpy as np
import pytest

import rollerpy
from rollerpy.outputs import read_rows, read_summary
from rollerpy.paths import PROBLEMS, ROOT
from rollerpy.vtu import available_steps, read_vtu, vtu_path

HERTZ = os.path.join(PROBLEMS, "hertz.toml")


def assert_table_equals_csv(table, path, skip=()):
    """Every cell of the table equals the CSV's (reals are written round-trip exact); `skip`: timings."""
    rows = read_rows(str(path))
    assert list(table) == list(rows[0]) and all(len(v) == len(rows) for v in table.values())
    for column, values in table.items():
        if column in skip:
            continue
        written = [r[column] for r in rows]
        if values.dtype.kind == "U":
            assert list(values) == written, column
        else:
            np.testing.assert_array_equal(values, np.array([float(w) for w in written]), err_msg=f"{path}: {column}")


def test_results_in_memory_equal_the_files_of_the_same_run(tmp_path):
    out = tmp_path / "hertz"
    run = rollerpy.run(HERTZ, set={"steps.count": 3, "roller.path[0].steps": [1, 3]}, out=out)
    assert run.ok and run.steps_done == 3 and run.written_steps == [0, 1, 2, 3]
    for name in ("roller", "contact", "solver"):
        assert_table_equals_csv(run.table(name), out / f"{name}.csv", skip=("wall_s", "ipopt_time_s"))
    assert list(run.solver["status"]) == ["converged"] * 3
    for step in run.written_steps:
        vtu = read_vtu(vtu_path(str(out), step))
        np.testing.assert_array_equal(run.mesh.points, vtu.reference)
        fields = run.at_step(step)
        for name, values in vtu.point_data.items():
            mine = fields[name]
            np.testing.assert_array_equal(mine, values[:, :mine.shape[1]] if mine.ndim == 2 else values,
                                          err_msg=f"step {step}: {name}")
        for name, values in vtu.cell_data.items():
            np.testing.assert_array_equal(fields[name], values, err_msg=f"step {step}: {name}")
    assert read_summary(str(out))["status"] == "completed"


def test_without_out_no_file_is_written_and_the_answer_is_hertz(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    scene = tomllib.load(open(HERTZ, "rb"))
    del scene["roller"]["path"][0]["dy"]
    run = rollerpy.run(scene, set={"roller.path[0].p0": 2000.0})
    assert os.listdir(tmp_path) == []
    # The peak of the nodal pressure on the graded mesh against the prescribed Hertz peak.
    assert run.field("contact_pressure").max() == pytest.approx(2000.0, rel=0.01)
    e_star = 2.1e5 / (1 - 0.3**2)
    assert run.roller["fy"][-1] == pytest.approx(np.pi * 100.0 * 2000.0**2 / e_star, rel=1e-6)


def test_an_elastic_roller_gives_its_disc_with_the_fields():
    run = rollerpy.run(HERTZ, set={"roller.E": 2.1e5, "roller.nu": 0.3})
    disc = run.fields[-1].roller["disc"]
    n, m = len(disc["points"]), len(disc["cells"])
    assert disc["points"].shape == (n, 2) and disc["cells"].shape == (m, 4) and disc["cell_type"] == "Q4"
    assert disc["point_data"]["displacement"].shape == (n, 3) and disc["cell_data"]["stress"].shape == (m, 6)
    # The disc carries the strip's force on the roller; its points lie about the roller's centre.
    np.testing.assert_allclose(disc["point_data"]["contact_force"][:, 1].sum(), run.roller["fy"][-1], rtol=1e-9)
    centre = np.array([run.fields[-1].roller["xc"], run.fields[-1].roller["yc"]])
    radius = np.linalg.norm(disc["points"] - centre, axis=1)
    assert abs(radius.max() - 100.0) < 1e-9
    assert "disc" not in rollerpy.run(HERTZ, set={"steps.count": 1}).fields[-1].roller  # a rigid roller


def test_a_scene_from_a_dict_gives_the_results_of_its_file():
    scene = tomllib.load(open(HERTZ, "rb"))
    from_dict = rollerpy.run(scene, set={"steps.count": 2, "roller.path[0].steps": [1, 2]})
    from_file = rollerpy.run(HERTZ, set={"steps.count": 2, "roller.path[0].steps": [1, 2]})
    for column in from_file.roller:
        np.testing.assert_array_equal(from_dict.roller[column], from_file.roller[column])
    np.testing.assert_array_equal(from_dict.field("stress_nodal"), from_file.field("stress_nodal"))


def test_overrides_reach_path_segments_and_bad_ones_are_input_errors():
    deeper = rollerpy.load_scene(HERTZ, set={"roller.path[0].dy": -0.2})
    assert 'dy = -0.2' in deeper.toml()
    with pytest.raises(rollerpy.InputError, match="material.E"):
        rollerpy.load_scene(HERTZ, set={"material.E": "stiff"})
    with pytest.raises(rollerpy.InputError, match="roller.path\\[5\\]"):
        rollerpy.load_scene(HERTZ, set={"roller.path[5].dy": -0.2})
    with pytest.raises(rollerpy.InputError, match="material.nu: a value of Python type 'object'"):
        rollerpy.load_scene(HERTZ, set={"material.nu": object()})
    with pytest.raises(ValueError):  # InputError is a ValueError
        rollerpy.load_scene({"mesh": {"length": -1.0}})


def test_progress_sees_every_step_and_its_exception_stops_the_run():
    seen = []
    rollerpy.run(HERTZ, progress=lambda row: seen.append((row["step"], row["steps"], row["status"])))
    assert seen == [(s, 4, "converged") for s in (1, 2, 3, 4)]

    class Enough(Exception):
        pass

    def stop_at_two(row):
        if row["step"] == 2:
            raise Enough()

    with pytest.raises(Enough):
        rollerpy.run(HERTZ, progress=stop_at_two)


CTRL_C_SCRIPT = """
import sys
import rollerpy
try:
    rollerpy.run(sys.argv[1], set={"steps.count": 400, "roller.path[0].steps": [1, 400]}, out=sys.argv[2],
                 progress=lambda row: print("step", row["step"], flush=True))
except rollerpy.RunInterrupted as e:
    assert "resume=True" in str(e), str(e)
    print("interrupted", e.result.status, e.result.steps_done, len(e.result.roller["fy"]), flush=True)
"""

RESUME_SCRIPT = """
import sys
import rollerpy
run = rollerpy.run(sys.argv[1], set={"steps.count": 400, "roller.path[0].steps": [1, 400]}, out=sys.argv[2],
                   resume=True, progress=lambda row: print("step", row["step"], flush=True))
print("resumed", run.status, run.steps_done, len(run.roller["fy"]), len(run.solver["step"]), run.written_steps[0])
"""


def test_ctrl_c_stops_after_the_step_under_way_with_the_results_and_the_checkpoint(tmp_path):
    out = tmp_path / "hertz"
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    proc = subprocess.Popen([sys.executable, "-c", CTRL_C_SCRIPT, HERTZ, str(out)], env=env,
                            stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().startswith("step 1")
    proc.send_signal(signal.SIGINT)
    lines = proc.communicate(timeout=120)[0].splitlines()
    assert proc.returncode == 0
    word, status, steps_done, rows = lines[-1].split()
    assert word == "interrupted" and status == "interrupted"
    assert 1 <= int(steps_done) < 400 and int(rows) == int(steps_done) + 1  # the roller's row 0 too
    summary = read_summary(str(out))
    assert summary["status"] == "interrupted" and summary["steps_done"] == int(steps_done)
    assert (out / "checkpoint.cbor").exists()
    # rollerpy.run(..., resume=True) goes on from the checkpoint: the steps left, and the tables of
    # the whole run (the folder's), equal to its files.
    done = subprocess.run([sys.executable, "-c", RESUME_SCRIPT, HERTZ, str(out)], env=env, capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0] == "step %d" % (int(steps_done) + 1)
    word, status, steps, roller_rows, solver_rows, first_written = lines[-1].split()
    assert (word, status, int(steps)) == ("resumed", "completed", 400)
    assert int(roller_rows) == 401 and int(solver_rows) == 400 and int(first_written) == int(steps_done) + 1
    assert read_summary(str(out))["status"] == "completed"


def test_resume_needs_the_output_folder_and_the_names_are_in_dir():
    with pytest.raises(rollerpy.InputError, match="resume=True: give out"):
        rollerpy.run(HERTZ, resume=True)
    with pytest.raises(rollerpy.InputError, match="resume"):
        rollerpy.run(HERTZ, out="x", resume="yes")
    assert {"run", "load_scene", "RunResult", "RunInterrupted", "InputError"} <= set(dir(rollerpy))


def test_a_multi_pass_run_gives_the_verdict_and_the_tables_of_the_files(tmp_path):
    out = tmp_path / "p45"
    fatigue = {"fatigue.dang_van_a": 0.3, "fatigue.dang_van_limit": 300.0, "fatigue.shear_fatigue_limit": 300.0,
               "fatigue.critical_shear_strain": 11.0}
    run = rollerpy.run(os.path.join(PROBLEMS, "shakedown_p45.toml"),
                       set={"passes.method": "stationary", "passes.count": 3, **fatigue}, out=out)
    summary = read_summary(str(out))
    assert run.verdict["verdict"] == summary["passes"]["verdict"]
    assert_table_equals_csv(run.passes, out / "passes.csv")
    assert_table_equals_csv(run.residual_depth, out / "residual_depth.csv")
    # With [fatigue]: fatigue.csv's table and summary.json's fatigue block, as the files hold them.
    assert_table_equals_csv(run.fatigue, out / "fatigue.csv")
    assert run.fatigue_answer == summary["fatigue"] and run.fatigue_answer["pass"] == 3
    assert run.written_steps == available_steps(str(out)) and run.written_steps[-1] == 3


def test_pass_runs_write_each_pass_loaded_state_for_paraview(tmp_path):
    # Stationary: the pass's steady state under the roller beside the residual strip after it, at
    # time step - 1/2 in fields.pvd; the Hertz pressure on the loaded strip, none left after it.
    out = tmp_path / "stationary"
    run = rollerpy.run(os.path.join(PROBLEMS, "shakedown_p45.toml"),
                       set={"passes.method": "stationary", "passes.count": 2, "output.every": 1}, out=out)
    assert [(f.step, f.loaded) for f in run.fields] == [(0, False), (1, True), (1, False), (2, True), (2, False)]
    assert run.written_steps == [0, 1, 2] == available_steps(str(out))
    pvd = (out / "fields.pvd").read_text()
    order = [pvd.index(name) for name in ("step_0000.vtu", "step_0001_loaded.vtu", "step_0001.vtu",
                                          "step_0002_loaded.vtu", "step_0002.vtu")]
    assert order == sorted(order) and 'timestep="0.5"' in pvd and (out / "roller_0001_loaded.vtp").exists()
    loaded, residual = run.at_step(1, loaded=True), run.at_step(1)
    assert abs(loaded["contact_pressure"].max() / 2307.7 - 1.0) < 0.05  # Hertz's p0 of the scene
    # Under the roller (p0/k = 4.5) the perfectly plastic strip flows: von Mises at its yield stress.
    assert loaded["von_mises_nodal"].max() == pytest.approx(888.2312, rel=1e-9)
    assert loaded["von_mises_nodal"].max() > 1.2 * residual["von_mises_nodal"].max()
    assert abs(loaded["displacement"][:, 1]).max() > 2.0 * abs(residual["displacement"][:, 1]).max()
    on_disk = read_vtu(str(out / "step_0001_loaded.vtu"))
    assert np.array_equal(on_disk.point_data["contact_pressure"], loaded["contact_pressure"])
    # Transient: each pass's step in the middle of its travel (steps 4-5 of 7: step 4) beside its end.
    marched = rollerpy.run(os.path.join(PROBLEMS, "shakedown_p45.toml"),
                           set={"passes.count": 2, "steps.count": 7, "roller.path[1].steps": [4, 5],
                                "roller.path[1].dx": 2.0, "roller.path[2].steps": [6, 7], "output.every": 7})
    assert marched.written_steps == [0, 4, 7, 11, 14] and not any(f.loaded for f in marched.fields)
    assert marched.at_step(11)["contact_pressure"].max() > 1000.0
    assert marched.at_step(14)["contact_pressure"].max() == 0.0


@pytest.mark.parametrize("example", ["load_sweep", "stationary_carter"])
def test_the_documented_examples_draw_their_figures(tmp_path, example):
    figure = tmp_path / f"{example}.png"
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    subprocess.run([sys.executable, os.path.join(ROOT, "docs", "examples", f"{example}.py"), str(figure)],
                   cwd=ROOT, env=env, check=True, timeout=120)
    assert figure.stat().st_size > 10000


def test_two_threads_run_one_after_the_other_without_a_crash():
    """MUMPS's sequential build is not thread-safe: runs from two threads at once are serialised
    (the second waits), and both give the answer of a run alone."""
    import threading
    results, errors = [], []

    def one():
        try:
            results.append(rollerpy.run(HERTZ, set={"steps.count": 2, "roller.path[0].steps": [1, 2]}))
        except Exception as e:  # recorded, the test fails on it below
            errors.append(e)

    threads = [threading.Thread(target=one) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors and len(results) == 2 and all(r.ok for r in results)
    np.testing.assert_array_equal(results[0].roller["fy"], results[1].roller["fy"])


def test_a_run_from_a_progress_callback_is_refused():
    def nested(row):
        rollerpy.run(HERTZ, set={"steps.count": 1, "roller.path[0].steps": [1, 1]})

    with pytest.raises(rollerpy.InputError, match="from within a run"):
        rollerpy.run(HERTZ, set={"steps.count": 1, "roller.path[0].steps": [1, 1]}, progress=nested)


def test_python_values_are_taken_as_the_scene_file_would_hold_them_or_refused():
    with open(HERTZ, "rb") as f:
        scene = tomllib.load(f)
    # numpy's integers and floats are ints and floats; its arrays are lists.
    scene["steps"]["count"] = np.int64(2)
    scene["roller"]["path"][0]["steps"] = np.array([1, 2])
    scene["material"]["E"] = np.float64(scene["material"]["E"])
    assert rollerpy.run(scene).steps_done == 2
    refused = {
        "an integer beyond 64 bits": dict(set={"steps.count": 2 ** 70}),
        "expected a key of dotted names": dict(set={"": 1}),
        "expected a dict of overrides": dict(set="steps.count=2"),
        "expected None or an output folder": dict(out=5),
        "expected True or False": dict(verbose="no"),
        "expected None or a function": dict(progress=5),
    }
    deep = x = {}
    for _ in range(100000):
        x["a"] = {}
        x = x["a"]
    refused["nested deeper than 100 levels"] = dict(set={"material.E": deep})
    for message, kwargs in refused.items():
        with pytest.raises(rollerpy.InputError, match=message):
            rollerpy.run(HERTZ, **kwargs)
    with pytest.raises(rollerpy.InputError, match="expected a scene file's path"):
        rollerpy.run(None)
    with pytest.raises(rollerpy.InputError, match="nested deeper than 100 levels"):
        rollerpy.run(deep)
