"""One point of a study: one roller process with the point's --set values, its output folder
kept, and what the study collects from it. run_point() runs where a Dask worker runs it, so it
takes plain data and returns plain data; it never raises for a failing run (the failure is the
point's result: status and message)."""
import os

from ..outputs import collect
from ..runner import Status, contact_option, read_record, roller_command, run, set_options, write_record

RECORD = "point.json"


def command(roller, scene, backend, set_values, out):
    return roller_command(roller, scene, out, "--overwrite", *contact_option(backend), *set_options(set_values))


def make_task(index, name, cmd, out, backend=None, values=None, timeout=1e7, collect=(), env=None):
    """The plain data run_point() takes (what a Dask worker receives)."""
    return {"index": index, "name": name, "backend": backend, "values": values or {}, "cmd": cmd, "out": out,
            "timeout": timeout, "collect": list(collect), "env": env or {}}


def run_point(task):
    """task: make_task()'s dict. Returns the point's record (also written to OUT/point.json, the
    mark of a complete point for --resume)."""
    out = task["out"]
    os.makedirs(out, exist_ok=True)
    result = run(task["cmd"], os.path.join(out, "run.log"), task["timeout"], task["env"])
    status, message = result.status, result.last_line()
    if status == Status.TIMEOUT:
        message = "no result within %g s (study timeout)" % task["timeout"]
    elif status == Status.CRASHED:
        message = "exit %s: %s" % (result.exit_code, message)
    record = {"index": task["index"], "name": task["name"], "backend": task["backend"], "values": task["values"],
              "status": status.value, "message": message, "wall_s": round(result.wall_s, 3), "out": out,
              "collected": collect(out, task["collect"]), "command": task["cmd"]}
    write_record(os.path.join(out, RECORD), record)
    return record


def lost_record(task, message):
    """The record of a point that did not run (its task failed on the cluster): status crashed,
    and no point.json, so --resume runs it again."""
    return {"index": task["index"], "name": task["name"], "backend": task["backend"], "values": task["values"],
            "status": Status.CRASHED.value, "message": message, "wall_s": 0.0, "out": task["out"], "collected": {},
            "command": task["cmd"]}


def finished_record(out, task):
    """The record of a point already complete in `out` with the same command, else None."""
    record = read_record(os.path.join(out, RECORD))
    return record if record and record.get("command") == task["cmd"] else None
