"""A study stopped by the user (`rollerpy study`, docs/studies.md): Ctrl-C (SIGINT to the
study's process group, as a terminal sends it) or SIGTERM ends it with one line and exit code 130
(143), no roller process left running, study.csv holding the finished points, and --resume runs
only the others; an unreachable --scheduler ends with one line naming the address, exit code 2."""
import os
import signal
import socket
import subprocess
import time

import pytest
from conftest import LAUNCHER
from test_study import BLOCK, roller_processes_in, run_study, write

from rollerpy.outputs import read_rows

SLOW = """
scene = "%s"
collect = ["converged"]
[set]
"steps.count" = 2
"mesh.refine" = 6
[grid]
"material.E" = [1.0e5, 1.5e5, 2.0e5, 2.5e5]
""" % BLOCK


def finished(out):
    points = os.path.join(out, "points")
    return [d for d in os.listdir(points) if os.path.exists(os.path.join(points, d, "point.json"))] \
        if os.path.isdir(points) else []


@pytest.mark.parametrize("engine, signum", [(["--serial"], signal.SIGINT), (["--jobs", "2"], signal.SIGINT),
                                            (["--serial"], signal.SIGTERM)])
def test_an_interrupted_study_says_so_in_one_line_and_resumes(roller, tmp_path, engine, signum):
    study, out = write(str(tmp_path), "slow.toml", SLOW), str(tmp_path / "out")
    table = os.path.join(out, "study.csv")
    proc = subprocess.Popen([LAUNCHER, "study", study, "--out", out, "--quiet", "--roller", roller] + engine,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        deadline = time.monotonic() + 120  # until study.csv holds a finished point
        while time.monotonic() < deadline and not (os.path.exists(table) and read_rows(table)):
            time.sleep(0.02)
        os.killpg(proc.pid, signum)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == 128 + signum, err
    done = len(read_rows(table))
    assert err.strip().splitlines() == ["study: interrupted after %d of 4 points; rerun with --resume" % done]
    assert 1 <= done < 4
    deadline = time.monotonic() + 5  # the runs die with their parent: no orphan writes into out
    while roller_processes_in(out) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert roller_processes_in(out) == []
    complete = len(finished(out))  # done, or one more that ended as the signal came
    r = run_study(roller, study, "--out", out, "--serial", "--resume")
    assert r.returncode == 0, r.stderr
    assert "4 points (%d complete, %d to run)" % (complete, 4 - complete) in r.stdout
    assert [g["status"] for g in read_rows(os.path.join(out, "study.csv"))] == ["ok"] * 4


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.parametrize("address, expected", [
    ("tcp://127.0.0.1:%d", "no Dask scheduler answered within 10 s"),
    ("127.0.0.1", "not an address")])
def test_an_unreachable_scheduler_is_one_line_and_exit_2(roller, tmp_path, address, expected):
    study = write(str(tmp_path), "slow.toml", SLOW)
    address = address % free_port() if "%d" in address else address
    t0 = time.monotonic()
    r = run_study(roller, study, "--out", str(tmp_path / "out"), "--scheduler", address)
    assert r.returncode == 2
    assert time.monotonic() - t0 < 30  # the connect timeout, not Dask's default
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("study: --scheduler %s: %s" % (address, expected))
    assert "dask-scheduler --port" in lines[0] or "expected tcp://HOST:PORT" in lines[0]
