"""What the fuzzers beside fuzz-scenes share (fuzz-shakedown-limit, fuzz-python, fuzz-study;
docs/stability.md, "Hostile input"): their common options, the work and failures folders, the
tally of outcomes, a failing case's reproducer (OUT/failures/<case>/ with command.txt: the reason,
the shell lines that set the case up and the command; output.txt; copies of the case's files; the
case's folder OUT/work/<case>/, which the command names, is kept) and the closing line."""
import os
import random
import shlex
import shutil
import time

from ..command import parser
from ..paths import DEFAULT_ROLLER, ROOT


def options(name, doc, cases, timeout):
    """The parser of a fuzzer: --cases, --seed, --roller, --out (default out/<name>), --timeout,
    --sanitized (ROLLER is a sanitizer build: fewer and smaller cases)."""
    ap = parser(name, doc)
    ap.add_argument("--cases", type=int, default=cases)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--roller", default=DEFAULT_ROLLER)
    ap.add_argument("--out", default=os.path.join(ROOT, "out", name))
    ap.add_argument("--timeout", type=float, default=timeout, help="per case [s]")
    ap.add_argument("--sanitized", action="store_true", help="ROLLER is a sanitizer build (ROLLER_SANITIZE)")
    return ap


class Campaign:
    """One fuzzer's run: OUT/work/ for the cases (cleared first), OUT/failures/ for reproducers."""

    def __init__(self, name, args):
        self.name, self.args = name, args
        self.rng = random.Random(args.seed)
        self.work = os.path.join(args.out, "work")
        self.failures = os.path.join(args.out, "failures")
        shutil.rmtree(args.out, ignore_errors=True)
        os.makedirs(self.work)
        self.counts, self.n_failed, self.t0 = {}, 0, time.monotonic()

    def case_dir(self, case):
        """The case's own folder, OUT/work/<case>/ (removed when the case passes)."""
        d = os.path.join(self.work, "%04d" % case)
        os.makedirs(d)
        return d

    def record(self, case, outcome, problem, what, command, output, files=(), env=None, setup=()):
        """Counts the outcome; a problem (non-empty) saves the reproducer and prints one line, else
        the case's folder goes. setup: shell lines that make the case's files again."""
        self.counts[outcome] = self.counts.get(outcome, 0) + 1
        if not problem:
            shutil.rmtree(os.path.join(self.work, "%04d" % case), ignore_errors=True)
            return
        self.n_failed += 1
        d = os.path.join(self.failures, "%04d" % case)
        os.makedirs(d)
        for path in files:
            if os.path.isfile(path) and not os.path.islink(path):
                shutil.copy(path, d)
        env_words = ["%s=%s" % kv for kv in sorted((env or {}).items())]
        with open(os.path.join(d, "command.txt"), "w") as f:
            f.write("# %s: %s\n%s%s\n" % (problem, what, "".join(line + "\n" for line in setup),
                                          shlex.join(env_words + [str(c) for c in command])))
        with open(os.path.join(d, "output.txt"), "w", errors="replace") as f:
            f.write(output)
        print("case %4d FAILED %s: %s -> %s" % (case, problem, what[:300], d), flush=True)

    def finish(self, note=""):
        """The closing line; exit code 0 when every case passed, 1 otherwise."""
        print("%s: %d cases in %.0f s (seed %d%s), outcomes %s%s; %d failed" % (
            self.name, self.args.cases, time.monotonic() - self.t0, self.args.seed,
            ", sanitized" if self.args.sanitized else "",
            ", ".join("%s: %d" % kv for kv in sorted(self.counts.items())), note, self.n_failed))
        return 1 if self.n_failed else 0
