"""The runner (rollerpy.runner): a run's exit code, log and status; a timeout kills the run and
its children; a run that must succeed raises with its log; records are written whole or not at
all."""
import os
import time

import pytest

from rollerpy import runner
from rollerpy.paths import PROBLEMS


def alive(pid):
    """Whether the process runs (a zombie, killed but not yet reaped, does not)."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_exit_code_log_and_status(tmp_path):
    log = str(tmp_path / "sub" / "run.log")
    result = runner.run(["sh", "-c", 'echo first; echo "$GREETING" >&2; exit 3'], log, env={"GREETING": "last"})
    assert (result.exit_code, result.timed_out, result.status) == (3, False, runner.Status.OUT_OF_MEMORY)
    assert result.output() == "first\nlast\n" and result.last_line() == "last"
    with pytest.raises(runner.RunFailed, match="exit 3"):
        result.check()
    assert runner.run(["true"], log).check().status == runner.Status.OK
    assert runner.run(["sh", "-c", "kill -9 $$"], log).status == runner.Status.CRASHED


def test_a_timeout_kills_the_run_and_its_children(tmp_path):
    pid_file = str(tmp_path / "child.pid")
    t0 = time.monotonic()
    result = runner.run(["sh", "-c", "sleep 60 & echo $! > %s; wait" % pid_file], str(tmp_path / "log"), timeout=1.0)
    assert time.monotonic() - t0 < 10
    assert result.timed_out and result.exit_code is None and result.status == runner.Status.TIMEOUT
    with open(pid_file) as f:
        child = int(f.read())
    time.sleep(0.2)
    assert not alive(child)  # the child in the run's process group was killed with it


def test_roller_exit_codes(roller, tmp_path):
    out = str(tmp_path / "out")
    bad = runner.roller_command(roller, os.path.join(PROBLEMS, "hertz.toml"), out, "--set", "material.nu=0.7")
    result = runner.run(bad, out + ".log")
    assert result.exit_code == 2 and result.status == runner.Status.INPUT_ERROR
    assert "material.nu" in result.output()
    good = runner.roller_command(roller, os.path.join(PROBLEMS, "hertz.toml"), out, "--steps", 1,
                                 *runner.contact_option("penalty"), *runner.set_options([("material.E", "2.0e5")]))
    assert good[-6:] == ["--steps", "1", "--contact", "penalty", "--set", "material.E=2.0e5"]
    assert runner.run(good, out + ".log").check().status == runner.Status.OK


def test_records_are_whole_or_absent(tmp_path):
    path = str(tmp_path / "point.json")
    assert runner.read_record(path) is None
    runner.write_record(path, {"status": "ok", "values": [1, 2]})
    assert runner.read_record(path) == {"status": "ok", "values": [1, 2]}
    with pytest.raises(RuntimeError):
        with runner.atomic_file(path) as f:
            f.write('{"status": "cut')
            raise RuntimeError("the writer dies half-way")
    assert runner.read_record(path) == {"status": "ok", "values": [1, 2]}  # the old record, whole
    with open(path, "w") as f:
        f.write('{"status": ')
    assert runner.read_record(path) is None
