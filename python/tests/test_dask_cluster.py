"""A study on a Dask cluster of separate processes, started as on a real cluster
(docs/studies.md, Engines): Debian's `dask-scheduler` and two `dask-worker` processes on
localhost, the study sent with --scheduler tcp://127.0.0.1:PORT, its study.csv values equal to a
--serial run's. Every process is stopped at the end, also when the test fails."""
import os
import signal
import subprocess
import time

import pytest
from test_study import TINY, run_study, write
from test_study_interrupt import free_port

from rollerpy.outputs import read_rows


def start(cmd, log):
    with open(log, "w") as f:  # the child keeps its own descriptor
        return subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, start_new_session=True)


def stop(procs):
    for p in procs:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGTERM)
    for p in procs:
        try:
            p.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()


@pytest.fixture
def cluster(tmp_path):
    """dask-scheduler and two dask-worker processes (one thread each) on a free port; yields the
    scheduler's address once both workers are connected."""
    address = "tcp://127.0.0.1:%d" % free_port()
    port = address.rsplit(":", 1)[1]
    procs = [start(["dask-scheduler", "--host", "127.0.0.1", "--port", port, "--no-dashboard"],
                   str(tmp_path / "scheduler.log"))]
    try:
        for i in range(2):
            procs.append(start(["dask-worker", address, "--nthreads", "1", "--nworkers", "1", "--no-dashboard",
                                "--name", "worker%d" % i, "--local-directory", str(tmp_path / ("w%d" % i)),
                                "--death-timeout", "60"], str(tmp_path / ("worker%d.log" % i))))
        from distributed import Client
        with Client(address, timeout=30) as client:
            client.wait_for_workers(2, timeout=60)
            assert len(client.scheduler_info()["workers"]) == 2
        yield address
    finally:
        stop(procs[::-1])


def test_a_study_on_a_scheduler_and_two_workers_gives_the_serial_values(roller, tmp_path, cluster):
    study = write(str(tmp_path), "tiny.toml", TINY)
    t0 = time.monotonic()
    r = run_study(roller, study, "--out", str(tmp_path / "cluster"), "--scheduler", cluster)
    assert r.returncode == 0, r.stderr
    assert "on %s" % cluster in r.stdout
    assert time.monotonic() - t0 < 120
    r = run_study(roller, study, "--out", str(tmp_path / "serial"), "--serial")
    assert r.returncode == 0, r.stderr
    a = read_rows(str(tmp_path / "serial" / "study.csv"))
    b = read_rows(str(tmp_path / "cluster" / "study.csv"))
    same = ["index", "backend", "material.E", "material.nu", "converged", "iterations_total",
            "solver.csv:residual", "solver.csv:iterations", "status"]
    assert len(a) == 4 and all(row["status"] == "ok" for row in a)
    assert [[row[k] for k in same] for row in a] == [[row[k] for k in same] for row in b]
