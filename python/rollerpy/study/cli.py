"""Runs a study: every point of a study file (docs/studies.md), in parallel local processes
through Dask's LocalCluster by default, on a running Dask scheduler with --scheduler, or
serially with --serial.

usage: ./rollerpy study STUDY.toml [--out DIR] [--jobs N] [--scheduler tcp://HOST:8786]
                         [--serial] [--resume] [--roller build/roller] [--quiet]

Writes DIR/study.csv (one row per point: index, backend, the varied parameters, the collected
values, status, message, wall time, output folder) after every finished point, and keeps every
point's output folder DIR/points/pNNN_BACKEND/ with its run.log and point.json. A point that
fails (a step that does not converge, bad input, a crash, the study's timeout) is recorded with
its status and message and the study goes on; exit code 0 when every point ran (whatever their
status), 2 for a bad study file or an unreachable scheduler, 130 (143) after Ctrl-C (SIGTERM),
which stops the running points and keeps study.csv of the finished ones. --resume skips the
points whose point.json is there with the same command (an interrupted study loses at most the
points that were running). Each roller
process is given one BLAS thread when points run side by side (--jobs > 1 or a scheduler).
Default DIR: out/studies/<study file name>; default --jobs: the number of cores.
"""
import contextlib
import os
import signal
import sys
import time

from ..command import parser
from ..paths import DEFAULT_ROLLER, ROOT
from . import engines, table
from .point import command, finished_record, make_task, run_point
from .study_file import StudyError, load, toml_value


def tasks_of(study, args):
    fixed = [(k, toml_value(v)) for k, v in study.fixed.items()]
    parallel = args.scheduler is not None or (not args.serial and args.jobs != 1)
    env = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"} if parallel else {}
    tasks = []
    for p in study.points:
        out = os.path.join(args.out, "points", p.name)
        varied = [(k, toml_value(p.values[k])) for k in study.parameters]
        cmd = command(args.roller, study.scene, p.backend, fixed + varied, out)
        tasks.append(make_task(p.index, p.name, cmd, out, backend=p.backend, values=p.values, timeout=study.timeout,
                               collect=study.collect, env=env))
    return tasks


def main(argv=None):
    ap = parser("study", __doc__)
    ap.add_argument("study")
    ap.add_argument("--out")
    ap.add_argument("--jobs", type=int, default=os.cpu_count())
    ap.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://127.0.0.1:8786")
    ap.add_argument("--serial", action="store_true", help="run the points one after the other without Dask")
    ap.add_argument("--resume", action="store_true", help="skip the points already complete in --out")
    ap.add_argument("--roller", default=DEFAULT_ROLLER)
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    args = ap.parse_args(argv)
    try:
        study = load(args.study)
    except StudyError as e:
        print("study: %s" % e, file=sys.stderr)
        return 2
    if args.jobs is None or args.jobs < 1:
        print("study: --jobs %s: expected at least 1" % args.jobs, file=sys.stderr)
        return 2
    if args.serial and args.scheduler:
        print("study: --serial and --scheduler exclude each other", file=sys.stderr)
        return 2
    args.roller = os.path.abspath(args.roller)
    if not os.access(args.roller, os.X_OK):
        print("study: --roller %s: not an executable (build first: bash scripts/build.sh)" % args.roller,
              file=sys.stderr)
        return 2
    args.out = os.path.abspath(args.out or os.path.join(ROOT, "out", "studies",
                                                        os.path.splitext(os.path.basename(study.path))[0]))
    os.makedirs(os.path.join(args.out, "points"), exist_ok=True)
    tasks = tasks_of(study, args)
    records, pending = [], []
    for task in tasks:
        done = finished_record(task["out"], task) if args.resume else None
        (records.append(done) if done else pending.append(task))
    csv_path = os.path.join(args.out, "study.csv")
    engine = "serial" if args.serial else (args.scheduler or "LocalCluster with %d workers" % args.jobs)
    print("study '%s': %d points (%d complete, %d to run) on %s -> %s" % (
        study.title, len(tasks), len(records), len(pending), engine, csv_path), flush=True)
    table.write(study, records, csv_path)

    from tqdm import tqdm
    bar = tqdm(total=len(tasks), initial=len(records), unit="point", disable=args.quiet, file=sys.stderr)
    failures = sum(r["status"] != "ok" for r in records)
    bar.set_postfix(failures=failures)
    t0 = time.monotonic()

    def on_done(record):
        nonlocal failures
        records.append(record)
        failures += record["status"] != "ok"
        table.write(study, records, csv_path)
        bar.update(1)
        bar.set_postfix(failures=failures)
        if record["status"] != "ok":
            bar.write("point %s: %s: %s" % (record["name"], record["status"], record["message"]))

    try:
        with interrupts():
            if pending and args.serial:
                engines.run_serial(pending, run_point, on_done)
            elif pending:
                engines.run_dask(pending, run_point, on_done, jobs=args.jobs, scheduler=args.scheduler)
    except engines.SchedulerUnreachable as e:
        bar.leave = False  # the bar is cleared: the message is the one line left
        bar.close()
        print("study: %s" % e, file=sys.stderr)
        return 2
    except Interrupted as e:
        bar.leave = False
        bar.close()
        print("study: interrupted after %d of %d points; rerun with --resume" % (len(records), len(tasks)),
              file=sys.stderr)
        return 128 + e.signum
    bar.close()
    print("study: %d points, %d failed, %.1f s -> %s" % (len(records), failures, time.monotonic() - t0, csv_path))
    return 0


class Interrupted(BaseException):
    """SIGINT or SIGTERM (a BaseException as KeyboardInterrupt: no `except Exception` stops it)."""

    def __init__(self, signum):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum


@contextlib.contextmanager
def interrupts():
    """Ctrl-C (SIGINT) and SIGTERM raise Interrupted inside the block: the running points are
    stopped (the runner kills their roller processes, Dask's clean-up its workers) and study.csv,
    written after every point, keeps the finished ones. Further signals are ignored during that
    clean-up, so that a second Ctrl-C does not end it half-way with a traceback."""
    def handler(signum, frame):
        for s in (signal.SIGINT, signal.SIGTERM):
            signal.signal(s, signal.SIG_IGN)
        raise Interrupted(signum)
    before = {s: signal.signal(s, handler) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for s, h in before.items():
            signal.signal(s, h)
