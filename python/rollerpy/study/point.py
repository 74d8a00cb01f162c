"""One point of a study: one roller process with the point's --set values, its output folder
kept, and what the study collects from it. run_point() runs where a Dask worker runs it, so it
takes plain data and returns plain data; it never raises for a failing run (the failure is the
point's result: status and message)."""
import csv
import json
import os
import shutil
import signal
import subprocess
import time

# Exit codes of roller run (docs/stability.md, docs/scenes.md): 0 converged, 1 a step failed, 2 bad
# input, 3 not enough memory; anything else (4: an internal error, a signal) is a crash.
STATUS = {0: "ok", 1: "failed", 2: "input_error", 3: "out_of_memory"}
RECORD = "point.json"


def command(roller, scene, backend, set_values, out):
    cmd = [roller, "run", scene, "--out", out, "--overwrite"] + (["--contact", backend] if backend else [])
    for key, literal in set_values:
        cmd += ["--set", "%s=%s" % (key, literal)]
    return cmd


def _last_line(text):
    lines = [l.strip() for l in text.splitlines() if l.strip()]
    return lines[-1] if lines else ""


def collect_values(out, fields):
    """The collected fields of a finished run: summary.json dotted paths, FILE.csv:COLUMN from
    the last row; None where a run did not write them."""
    summary = None
    try:
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
    except (OSError, ValueError):
        pass
    values = {}
    for name in fields:
        value = None
        if ":" in name:
            file, column = name.split(":", 1)
            try:
                with open(os.path.join(out, file), newline="") as f:
                    rows = list(csv.DictReader(f))
                value = rows[-1].get(column) if rows else None
            except OSError:
                pass
        elif summary is not None:
            value = summary
            for part in name.split("."):
                value = value.get(part) if isinstance(value, dict) else None
        values[name] = value
    return values


def make_task(index, name, cmd, out, backend=None, values=None, timeout=1e7, collect=(), env=None):
    """The plain data run_point() takes (what a Dask worker receives)."""
    return {"index": index, "name": name, "backend": backend, "values": values or {}, "cmd": cmd, "out": out,
            "timeout": timeout, "collect": list(collect), "env": env or {}}


# The run dies with the process that started it (a killed study, a stopped Dask worker): left
# running, an orphan would go on writing into the folder that --resume hands to a new run of the
# same point. util-linux's setpriv (essential in Debian) sets the parent-death signal and execs a
# shell that runs the command only if its parent is still this process: a study killed between
# the fork and the prctl would otherwise leave the run behind. Without setpriv the run is started
# bare.
def _die_with_parent(cmd):
    if not shutil.which("setpriv"):
        return list(cmd)
    return ["setpriv", "--pdeathsig", "KILL", "--", "sh", "-c", 'test "$PPID" = %d && exec "$@"' % os.getpid(),
            "sh"] + list(cmd)


def run_logged(cmd, log, timeout, env=None):
    """Runs cmd in its own process group with its output in `log`; on the timeout kills that
    group (the run and its children, nothing else). If this process dies, the run is killed too.
    Returns (exit code or None, timed out, wall seconds)."""
    t0 = time.monotonic()
    with open(log, "w") as f:
        proc = subprocess.Popen(_die_with_parent(cmd), stdout=f, stderr=subprocess.STDOUT,
                                start_new_session=True, env=dict(os.environ, **(env or {})))
        try:
            rc, timed_out = proc.wait(timeout=timeout), False
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            rc, timed_out = None, True
    return rc, timed_out, time.monotonic() - t0


def run_point(task):
    """task: make_task()'s dict. Returns the point's record (also written to OUT/point.json, the
    mark of a complete point for --resume)."""
    out = task["out"]
    os.makedirs(out, exist_ok=True)
    log = os.path.join(out, "run.log")
    rc, timed_out, wall = run_logged(task["cmd"], log, task["timeout"], task["env"])
    with open(log, errors="replace") as f:
        message = _last_line(f.read())
    if timed_out:
        status, message = "timeout", "no result within %g s (study timeout)" % task["timeout"]
    else:
        status = STATUS.get(rc, "crashed")
        if status == "crashed":
            message = "exit %s: %s" % (rc, message)
    record = {"index": task["index"], "name": task["name"], "backend": task["backend"], "values": task["values"],
              "status": status, "message": message, "wall_s": round(wall, 3), "out": out,
              "collected": collect_values(out, task["collect"]), "command": task["cmd"]}
    tmp = os.path.join(out, RECORD + ".tmp")
    with open(tmp, "w") as f:
        json.dump(record, f, indent=1)
    os.replace(tmp, os.path.join(out, RECORD))
    return record


def finished_record(out, task):
    """The record of a point already complete in `out` with the same command, else None."""
    try:
        with open(os.path.join(out, RECORD)) as f:
            record = json.load(f)
    except (OSError, ValueError):
        return None
    return record if record.get("command") == task["cmd"] else None
