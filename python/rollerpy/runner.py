"""The one way to start roller (or a benchmark program): the command in its own process group
with its output in a log file, killed with its children at the timeout and when this process
dies; the result typed (RunResult, Status); records written whole or not at all."""
import contextlib
import enum
import json
import os
import shutil
import signal
import stat
import subprocess
import time
from dataclasses import dataclass


class Status(str, enum.Enum):
    """What a run came to. Exit codes of roller run (docs/stability.md, docs/scenes.md): 0
    converged, 1 a step failed, 2 bad input, 3 not enough memory (or another system error);
    anything else (4: an internal error, a signal) is a crash."""
    OK = "ok"
    FAILED = "failed"
    INPUT_ERROR = "input_error"
    OUT_OF_MEMORY = "out_of_memory"
    CRASHED = "crashed"
    TIMEOUT = "timeout"


EXIT_STATUS = {0: Status.OK, 1: Status.FAILED, 2: Status.INPUT_ERROR, 3: Status.OUT_OF_MEMORY}


class RunFailed(RuntimeError):
    """A run that had to succeed did not; the message holds the command and the log's tail."""


@dataclass(frozen=True)
class RunResult:
    command: list
    log: str                # the file that holds the run's stdout and stderr
    exit_code: int | None   # None when killed at the timeout; negative: killed by that signal
    timed_out: bool
    wall_s: float

    @property
    def status(self):
        return Status.TIMEOUT if self.timed_out else EXIT_STATUS.get(self.exit_code, Status.CRASHED)

    def output(self):
        with open(self.log, errors="replace") as f:
            return f.read()

    def last_line(self):
        lines = [line.strip() for line in self.output().splitlines() if line.strip()]
        return lines[-1] if lines else ""

    def check(self):
        """Returns self when the run ended with exit code 0, else raises RunFailed."""
        if self.exit_code != 0:
            ended = "timed out" if self.timed_out else "exit %s" % self.exit_code
            raise RunFailed("%s\nroller failed (%s): %s" % (self.output()[-3000:], ended, " ".join(self.command)))
        return self


def roller_command(roller, scene, out, *options):
    """`roller run SCENE --out OUT` and further options (--contact, --set, --steps, ...)."""
    return [roller, "run", scene, "--out", out] + [str(o) for o in options]


def contact_option(backend):
    return ["--contact", backend] if backend else []


def set_options(values):
    """--set KEY=VALUE for each (key, TOML literal) pair."""
    options = []
    for key, literal in values:
        options += ["--set", "%s=%s" % (key, literal)]
    return options


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


def run(cmd, log, timeout=None, env=None):
    """Runs cmd in its own process group with its output in `log`; on the timeout [s] kills that
    group (the run and its children, nothing else). If this process dies, the run is killed too.
    env: variables added to this process's environment."""
    os.makedirs(os.path.dirname(os.path.abspath(log)), exist_ok=True)
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
        except BaseException:  # Ctrl-C, SIGTERM turned into an exception: the run ends with its caller
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            raise
    return RunResult(command=list(cmd), log=log, exit_code=rc, timed_out=timed_out, wall_s=time.monotonic() - t0)


def output_file_problem(path, option):
    """Why `path` cannot be a file the user named for writing ("" when it can): as roller's own
    --csv/--json (docs/reliability.md), only a new or a regular file in an existing folder."""
    if not path:
        return "%s '': expected a file name" % option
    if os.path.lexists(path) and not stat.S_ISREG(os.lstat(path).st_mode):
        return ("%s %s: something other than a regular file stands there (a folder, a link, a FIFO or a device); "
                "expected a new or a regular file" % (option, path))
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        return "%s %s: the folder %s does not exist" % (option, path, folder)
    return ""


@contextlib.contextmanager
def atomic_file(path, newline=None, mode="w"):
    """A file written whole or not at all: written beside as PATH.tmp (a regular file of ours,
    never through a link or into a FIFO), renamed on success."""
    tmp = path + ".tmp"
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_NOFOLLOW | os.O_NONBLOCK, 0o666)
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise OSError("%s: not a regular file; roller never writes through it" % tmp)
    try:
        with os.fdopen(fd, mode, **({} if "b" in mode else {"newline": newline})) as f:
            yield f
    except BaseException:
        os.unlink(tmp)
        raise
    os.replace(tmp, path)


def save_figure(fig, path, **savefig_options):
    """A matplotlib figure written atomically as PNG (the format from the name: .png)."""
    with atomic_file(path, mode="wb") as f:
        fig.savefig(f, format=os.path.splitext(path)[1][1:] or "png", **savefig_options)


def write_record(path, record):
    """A JSON record written atomically (a reader sees the old record or the new one)."""
    with atomic_file(path) as f:
        json.dump(record, f, indent=1)


def read_record(path):
    """The JSON record at path, or None when it is missing or unreadable."""
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None
