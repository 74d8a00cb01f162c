"""The study runner (`rollerpy study`, docs/studies.md): a 2 x 2 study on a LocalCluster with two
workers gives the same study.csv values as the points run serially; failing points (bad input,
the study's timeout) are recorded and the others complete; a study killed after some points and
rerun with --resume runs only the missing points; the study-file loader rejects unknown keys and
bad ranges with the file, the key and what was expected.
"""
import os
import signal
import subprocess
import time

import pytest
from conftest import LAUNCHER

from rollerpy.outputs import read_rows as rows
from rollerpy.paths import PROBLEMS
from rollerpy.study.study_file import StudyError, load

STUDY = [LAUNCHER, "study"]
BLOCK = os.path.join(PROBLEMS, "block_compression.toml")


def write(directory, name, text):
    path = os.path.join(directory, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def roller_processes_in(out):
    """Pids of the live processes whose command line names `out`."""
    pids = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                if out.encode() in f.read():
                    with open("/proc/%s/stat" % pid) as s:
                        if s.read().rsplit(")", 1)[1].split()[0] != "Z":
                            pids.append(int(pid))
        except OSError:
            pass
    return pids


def run_study(roller, *args):
    return subprocess.run(STUDY + list(args) + ["--roller", roller, "--quiet"], capture_output=True, text=True)


TINY = """
scene = "%s"
collect = ["converged", "iterations_total", "solver.csv:residual", "solver.csv:iterations"]
[set]
"steps.count" = 2
[grid]
"material.E" = [1.0e5, 2.0e5]
"material.nu" = { start = 0.2, stop = 0.3, count = 2 }
""" % BLOCK


@pytest.fixture
def folder(tmp_path):
    return str(tmp_path)


def error(folder, text):
    path = write(folder, "s.toml", text)
    with pytest.raises(StudyError) as e:
        load(path)
    assert path in str(e.value)
    return str(e.value)


def test_a_grid_expands_to_every_combination(folder):
    study = load(write(folder, "s.toml", TINY))
    assert len(study.points) == 4
    assert study.parameters == ["material.E", "material.nu"]
    assert [p.values for p in study.points][1] == {"material.E": 1.0e5, "material.nu": 0.3}


def test_ranges(folder):
    study = load(write(folder, "s.toml", TINY.replace("count = 2 }", "count = 3 }")))
    assert sorted({p.values["material.nu"] for p in study.points}) == [0.2, 0.25, 0.3]
    study = load(write(folder, "s.toml", TINY.replace("count = 2 }", "step = 0.05 }")))
    assert len({p.values["material.nu"] for p in study.points}) == 3


@pytest.mark.parametrize("text, expected", [
    (TINY.replace("collect", "colect"), "colect = ['converged', "),
    (TINY.replace("collect", "colect"), "unknown key; expected one of backends, collect"),
    (TINY.replace("count = 2", "count = 0"), "grid.material.nu.count = 0: expected an integer 1 <= count"),
    (TINY.replace("count = 2", "step = -0.1"), "grid.material.nu.step = -0.1: the step must go from start"),
    (TINY.replace("count = 2", "count = 2, step = 0.1"), "exactly one of count and step"),
    (TINY.replace("stop", "stpo"), "grid.material.nu.stpo"),
    (TINY.replace("[1.0e5, 2.0e5]", "[]"), "grid.material.E = []"),
    ('backends = ["simplex"]\n' + TINY, "backends = ['simplex']"),
    (TINY.replace(BLOCK, "nowhere.toml"), "scene = 'nowhere.toml': no such file"),
    (TINY + '[[point]]\n"material.E" = 1.0\n', "either as [grid]"),
    (TINY.replace('"steps.count" = 2', '"material.E" = 3.0'), "set.material.E"),
    ("scene = ", "not valid TOML"),
    (TINY.replace('collect = ["converged"', 'collect = ["wall_s"'),
     "collect = 'wall_s': study.csv has this column already"),
    (TINY.replace("solver.csv:iterations", "solver.csv:iterations:mean"),
     "collect = 'solver.csv:iterations:mean': the row choice 'mean': expected last, max, min or step=N"),
    (TINY.replace("solver.csv:iterations", "solver.csv:iterations:step=two"), "the row choice 'step=two'"),
    (TINY.replace("solver.csv:iterations", "solver:iterations"),
     "collect = 'solver:iterations': expected FILE.csv:COLUMN, optionally :last, :max, :min or :step=N"),
    (TINY.replace("solver.csv:iterations", "solver.csv:iterations:max:min"), "expected FILE.csv:COLUMN"),
    # A study reads the point's own output folder only.
    (TINY.replace("solver.csv:iterations", "/etc/x.csv:col"), "no absolute path and no '..'"),
    (TINY.replace("solver.csv:iterations", "../../x.csv:col"), "no absolute path and no '..'"),
    (TINY.replace("solver.csv:iterations", "sub/../../x.csv:col"), "no absolute path and no '..'"),
    (TINY.replace('"steps.count" = 2', '"steps.count" = ' + "[" * 2000 + "]" * 2000), "nested too deeply")])
def test_unknown_keys_and_bad_ranges_are_rejected(folder, text, expected):
    assert expected in error(folder, text)


def test_local_cluster_gives_the_serial_values(roller, folder):
    study = write(folder, "tiny.toml", TINY)
    serial, dask = os.path.join(folder, "serial"), os.path.join(folder, "dask")
    r = run_study(roller, study, "--out", serial, "--serial")
    assert r.returncode == 0, r.stderr
    r = run_study(roller, study, "--out", dask, "--jobs", "2")
    assert r.returncode == 0, r.stderr
    assert "LocalCluster with 2 workers" in r.stdout
    a, b = rows(os.path.join(serial, "study.csv")), rows(os.path.join(dask, "study.csv"))
    assert len(a) == 4
    same = ["index", "backend", "material.E", "material.nu", "converged", "iterations_total",
            "solver.csv:residual", "solver.csv:iterations", "status"]
    assert [[r[k] for k in same] for r in a] == [[r[k] for k in same] for r in b]
    assert all(r["status"] == "ok" and r["converged"] == "True" for r in a)
    assert all(os.path.isdir(r["out"]) for r in b)


def test_failing_points_are_recorded_and_the_others_complete(roller, folder):
    study = write(folder, "fail.toml", """
scene = "%s"
timeout = 10
collect = ["converged"]
[[point]]
"material.nu" = 0.7
"mesh.refine" = 1
"steps.count" = 2
[[point]]
"material.nu" = 0.3
"mesh.refine" = 1
"steps.count" = 2
[[point]]
"material.nu" = 0.3
"mesh.refine" = 10
"steps.count" = 1000
""" % BLOCK)
    # The timeout leaves the second point (0.2 s under the sanitizers) a wide margin when the
    # machine is loaded: with 2 s and a refine-40 mesh beside it, it once timed out in the
    # sanitized build under ctest -j2. The third point is long by its steps (0.5 s each in a
    # Release build), not by a mesh whose memory loads the machine.
    out = os.path.join(folder, "out")
    r = run_study(roller, study, "--out", out, "--jobs", "2")
    assert r.returncode == 0, r.stderr
    got = rows(os.path.join(out, "study.csv"))
    assert [g["status"] for g in got] == ["input_error", "ok", "timeout"]
    assert "material.nu" in got[0]["message"]
    assert got[1]["converged"] == "True"
    assert "no result within 10 s" in got[2]["message"]


def test_a_killed_study_resumes_with_the_missing_points_only(roller, folder):
    study = write(folder, "slow.toml", """
scene = "%s"
collect = ["converged", "iterations_total"]
[set]
"mesh.refine" = 6
[grid]
"steps.count" = [2, 60, 2, 2]
""" % BLOCK)
    out = os.path.join(folder, "out")
    proc = subprocess.Popen(STUDY + [study, "--out", out, "--serial", "--quiet", "--roller", roller],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    first = os.path.join(out, "points", "p000", "point.json")
    deadline = time.monotonic() + 120
    while not os.path.exists(first) and time.monotonic() < deadline:
        time.sleep(0.02)
    os.killpg(proc.pid, signal.SIGKILL)  # the study; the roller it runs has a session of its own
    proc.wait()
    assert os.path.exists(first)
    # The running point's roller dies with the study: an orphan would go on writing into the
    # folder the resumed study gives to the same point's new run. The point killed runs 60 steps
    # (4-15 s), so an orphan outlives the wait, which a loaded machine's teardown of the
    # killed process needs (0.25 s was too short beside the other tests).
    deadline = time.monotonic() + 2.0
    while roller_processes_in(out) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert roller_processes_in(out) == []
    done = sorted(d for d in os.listdir(os.path.join(out, "points"))
                  if os.path.exists(os.path.join(out, "points", d, "point.json")))
    assert len(done) < 4
    stamps = {d: os.path.getmtime(os.path.join(out, "points", d, "point.json")) for d in done}
    r = run_study(roller, study, "--out", out, "--serial", "--resume")
    assert r.returncode == 0, r.stderr
    assert "4 points (%d complete, %d to run)" % (len(done), 4 - len(done)) in r.stdout
    for d, t in stamps.items():  # not run again
        assert os.path.getmtime(os.path.join(out, "points", d, "point.json")) == t
    got = rows(os.path.join(out, "study.csv"))
    assert [g["status"] for g in got] == ["ok"] * 4
    assert [g["index"] for g in got] == ["0", "1", "2", "3"]


def test_collect_picks_a_row(roller, folder):
    """FILE.csv:COLUMN takes the last row; :max, :min, :last and :step=N the row they name (a
    multi-step Hertz run: fy grows with the indentation)."""
    picks = ["roller.csv:fy", "roller.csv:fy:last", "roller.csv:fy:max", "roller.csv:fy:min", "roller.csv:fy:step=2",
             "roller.csv:fy:step=99", "roller.csv:nothing:max"]
    study = write(folder, "hertz.toml", """
scene = "%s"
collect = [%s]
[[point]]
"material.nu" = 0.3
""" % (os.path.join(PROBLEMS, "hertz.toml"), ", ".join('"%s"' % p for p in picks)))
    r = run_study(roller, study, "--out", os.path.join(folder, "out"), "--serial")
    assert r.returncode == 0, r.stderr
    got = rows(os.path.join(folder, "out", "study.csv"))[0]
    fy = {int(row["step"]): row["fy"] for row in rows(os.path.join(got["out"], "roller.csv"))}
    assert got["roller.csv:fy"] == got["roller.csv:fy:last"] == fy[max(fy)]
    assert got["roller.csv:fy:max"] == max(fy.values(), key=float)
    assert got["roller.csv:fy:min"] == min(fy.values(), key=float)
    assert got["roller.csv:fy:step=2"] == fy[2] != fy[max(fy)]
    assert got["roller.csv:fy:step=99"] == got["roller.csv:nothing:max"] == ""


def test_collect_never_follows_a_link_out_of_the_point_folder(roller, folder):
    """A link in a point's folder that points outside it is not read: the cell stays empty."""
    outside = write(folder, "outside.csv", "step,secret\n1,4242\n")
    study = write(folder, "link.toml", """
scene = "%s"
collect = ["leak.csv:secret", "solver.csv:iterations"]
[[point]]
"steps.count" = 1
""" % BLOCK)
    out = os.path.join(folder, "out")
    r = run_study(roller, study, "--out", out, "--serial")
    assert r.returncode == 0, r.stderr
    point = rows(os.path.join(out, "study.csv"))[0]["out"]
    os.symlink(outside, os.path.join(point, "leak.csv"))
    from rollerpy.outputs import collect
    values = collect(point, ["leak.csv:secret", "solver.csv:iterations"])
    assert values["leak.csv:secret"] is None and values["solver.csv:iterations"] not in (None, "")
