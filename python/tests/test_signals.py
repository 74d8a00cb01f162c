"""Ctrl-C and SIGTERM stop a run cleanly (docs/scenes.md, Exit codes): the step under way ends,
summary.json says "interrupted" with exit code 128 + signal, the checkpoint is kept, and --resume
gives the uninterrupted run's files."""
import json
import os
import signal
import subprocess
import time

import pytest

from test_reliability import RESUME_COLUMNS, run, same_outputs, scene

SCENE, EXTRA = "z3_data01", []  # 73 short steps: a signal lands between two of them


def rows(path):
    try:
        with open(path) as f:
            return sum(1 for _ in f) - 1
    except FileNotFoundError:
        return 0


def interrupt(roller, out, signum, after_rows=5, timeout=120):
    """Starts the run, sends `signum` once solver.csv has `after_rows` rows; returns its exit code."""
    proc = subprocess.Popen([roller, "run", scene(SCENE), "--out", out] + EXTRA,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + timeout
    while rows(os.path.join(out, "solver.csv")) < after_rows:
        assert proc.poll() is None, "the run ended before it could be interrupted"
        assert time.time() < deadline, "no progress within %d s" % timeout
        time.sleep(0.01)
    proc.send_signal(signum)
    return proc.wait(timeout=timeout)


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_signal_stops_after_the_step_and_resumes(roller, tmp_path, signum):
    reference = str(tmp_path / "whole")
    rc, text = run(roller, ["run", scene(SCENE), "--out", reference] + EXTRA)
    assert rc == 0, text
    out = str(tmp_path / "interrupted")
    rc = interrupt(roller, out, signum)
    assert rc == 128 + signum
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    assert summary["status"] == "interrupted"
    assert summary["exit_code"] == rc
    steps = summary["steps_done"]
    assert 5 <= steps < summary["steps"], summary
    assert "--resume" in summary["message"]
    assert rows(os.path.join(out, "solver.csv")) == steps  # every row of the steps done, no more
    assert os.path.exists(os.path.join(out, "checkpoint.cbor"))
    rc, text = run(roller, ["run", scene(SCENE), "--out", out, "--resume"] + EXTRA)
    assert rc == 0, text
    problems = same_outputs(reference, out, RESUME_COLUMNS)
    assert not problems, "interrupted after step %d and resumed: %s" % (steps, "; ".join(problems))


# Two stationary passes on the roller's contact (about 3 s each): a signal sent during the second
# is heard inside its iteration, not after it.
STATIONARY = ["--set", 'passes.method="stationary"', "--set", 'passes.stationary_contact="roller"',
              "--set", "passes.count=2"]


def test_signal_stops_a_stationary_pass_inside_its_iteration_and_resumes(roller, tmp_path):
    reference = str(tmp_path / "whole")
    rc, text = run(roller, ["run", scene("shakedown_p45"), "--out", reference] + STATIONARY)
    assert rc == 0, text
    out = str(tmp_path / "interrupted")
    proc = subprocess.Popen([roller, "run", scene("shakedown_p45"), "--out", out] + STATIONARY,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 300
    while rows(os.path.join(out, "solver.csv")) < 1:  # pass 1 done: pass 2 under way
        assert proc.poll() is None, "the run ended before it could be interrupted"
        assert time.time() < deadline, "pass 1 did not end within 300 s"
        time.sleep(0.01)
    time.sleep(0.5)
    proc.send_signal(signal.SIGTERM)
    assert proc.wait(timeout=300) == 128 + signal.SIGTERM
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    # Heard after the pass, the run would have ended with pass 2 done (exit 0 or steps_done 2).
    assert summary["status"] == "interrupted" and summary["steps_done"] == 1, summary
    assert rows(os.path.join(out, "solver.csv")) == 1  # no row of the pass that was left
    rc, text = run(roller, ["run", scene("shakedown_p45"), "--out", out, "--resume"] + STATIONARY)
    assert rc == 0, text
    problems = same_outputs(reference, out, RESUME_COLUMNS)
    assert not problems, "a stationary pass interrupted and resumed: " + "; ".join(problems)
