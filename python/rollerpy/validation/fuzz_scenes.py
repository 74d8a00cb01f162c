"""Mutation fuzzer for scene files, --set values and command-line options (docs/stability.md,
"Hostile input").

usage: ./rollerpy fuzz-scenes [--cases 200] [--seed 1] [--roller ./build/roller]
                             [--out out/fuzz] [--timeout 30] [--steps 2] [--sanitized]
       ./rollerpy fuzz-scenes --scan FILE_OR_FOLDER...

Each case takes a shipped scene (problems/*.toml), mutates it (a line deleted or duplicated, a
value replaced by nan/inf/huge/tiny/negative/wrong-typed ones, the file truncated, binary garbage
inserted, deeply nested dotted keys, or a --set override of a random key with such a value) and
runs `roller run` on it for a few steps (--steps, default 2) under a timeout. One case in three
also varies the command line: one or more of `--steps 1|2|3` (instead of the default),
`--contact penalty|ipopt`, `--refine 1|2` (`--refine 2` with `--steps 1`), now and then an
invalid value of one of them (which must end in exit 2). Shares of their own (fuzz_shares):
5 % of the cases run a multi-pass scene (shakedown_case_hardened, shakedown_thin_strip,
shakedown_p45; 1-4 s each) with `passes.method = "stationary"`, 1 or 2 passes, both `stationary_contact`
values, `stationary_phases` 1 or 2, now and then `stationary_path_parts`, `until_verdict`,
`direction`, --refine 1, without --steps; one in seven of them sets a [passes] key to a value
that must be refused and one in ten adds --steps, which a multi-pass scene must refuse (exit 2 is
due); 8 % append [[layer]] blocks (1-3, or 200 thin ones; now and then a hostile value,
mesh.follow_layers) to a scene (the layered case_hardened is a seed as well); 4 % give one --set
key twice with nan or inf as one of the values (exit 2 is due).

A case passes when roller ends with a documented exit code (0 converged, 1 a step failed with an
"error:" line, 2 input error with "input error" or CLI11's "Run with --help", 3 a system error
such as a full disk) and no output file holds nan or inf. The output folder is scanned
recursively (rollerpy.scan): every CSV cell, JSON value (null counts), nan/inf token of the PVD
and TOML files, and every VTU file (step_NNNN.vtu) decoded array by array with numpy (rollerpy.vtu)
-- inline base64 binary data, raw or zlib-compressed (vtkZLibDataCompressor blocks; header_type
UInt32 or UInt64), or ascii -- for non-finite Float32/Float64 values; a VTU whose arrays cannot
be decoded or do not match the piece's point and cell counts (or a JSON file that does not parse)
is malformed. A case fails on
  - a sanitizer report in roller's output ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer",
    UBSan's "runtime error:"), whatever the exit code;
  - a crash (signal), a timeout (hang);
  - an internal error (exit 4, "roller: internal error:") or "roller: error:";
  - an undocumented exit code, or exit 1/2/3 without its message; another exit code where exit 2
    is due;
  - "exit 0 (converged) but nan/inf in an output": the run claimed success with a non-finite
    value in a file;
  - "nan/inf in an output after exit N" (a failed run must not write non-finite values either);
  - a malformed VTU or JSON file.
Every failing case leaves its reproducer in OUT/failures/<n>/ (scene.toml, command.txt with the
reason and the command, output.txt, and the flagged output files under outputs/). Before the
cases run, the scanner must find planted nan/inf values in generated CSV and VTU files (else exit
1). Exit code 0 when every case passed, 1 otherwise.

--sanitized: ROLLER is a sanitizer build (ROLLER_SANITIZE, Debug + ASan/UBSan, ~10x slower):
no burnishing scene, --steps 1 by default (1 or 2 in the command-line share), no --refine 2. The
sanitizer options of scripts/test_sanitized.sh (ASAN_OPTIONS abort_on_error=1 etc., the leak
suppressions) are set for roller when the environment does not set them.

--scan: decode the given output files (or every file under the given folders) and print, for a
VTU, each array's name, type and shape; exit code 1 when any holds nan/inf or is malformed.

The CTest "fuzz" label runs a short fixed-seed variant (300 cases); a sanitizer build
(-DROLLER_SANITIZE=ON) also runs 40 cases with --sanitized under the "fast" label
(scripts/test_sanitized.sh; there the pass share takes shakedown_case_hardened, one pass). A
long run for a night: --cases 10000 --seed $RANDOM. The other ways in have fuzzers of their own:
fuzz-shakedown-limit, fuzz-python (rollerpy.run), fuzz-study (their modules' docstrings).
"""
import os
import random
import re
import shlex
import shutil
import time
from dataclasses import dataclass

from ..command import parser
from ..paths import DEFAULT_ROLLER, PROBLEMS, ROOT
from ..runner import roller_command, run
from ..scan import FolderScan, Finding, files_under, scan_file, scan_outputs, self_check
from ..vtu import decode_vtu
from .fuzz_shares import PASS_SEEDS, SMALL_PASS_SEEDS, layer_case, pass_case, twice_case

# Scenes that run on their own (z3_data02 needs z3_data01's final state); small ones weigh more.
SEEDS = ["block_compression", "hertz", "cattaneo", "bar_impact", "z1_outf05", "z2_infini", "z2_large",
         "z4_v25", "stability_thin", "rolling_friction", "hertz_nu049", "block_compression", "hertz",
         "cattaneo_mindlin", "case_hardened", "burnishing"]
# For a Debug + ASan binary (--sanitized): the scenes whose first two steps take at most 0.2 s
# with the release build (burnishing: 0.3 s for one step, 1 s when a mutation makes it fail).
SMALL_SEEDS = [s for s in SEEDS if s != "burnishing"]
# The shares of the cases (fuzz_shares): multi-pass scenes solved with the stationary method,
# [[layer]] blocks added, a --set key given twice with a non-finite value.
PASS_SHARE, LAYER_SHARE, TWICE_SHARE = 0.05, 0.08, 0.04
HOSTILE_NUMBERS = ["nan", "inf", "-inf", "0", "-0.0", "-1", "1e308", "-1e308", "1e-308", "1e-300", "1e300",
                   "4294967297", "9007199254740993", "-4294967298", "2147483648", "1e20", "0.5", "3"]
WRONG_TYPES = ['"x"', "true", "[]", "{}", "[1, 2, 3]", '""', "{ value = nan }", "[nan, 0.0]"]
NUMBER = re.compile(r"^(\s*[A-Za-z_][A-Za-z0-9_]*\s*=\s*)(.+?)(\s*#.*)?$")
# Invalid values of the command-line options: CLI11 must reject them (exit 2, "Run with --help").
BAD_OPTIONS = [["--steps", "0"], ["--steps", "-1"], ["--steps", "1000001"], ["--steps", "x"], ["--steps", "1.5"],
               ["--refine", "0"], ["--refine", "65"], ["--refine", "nan"], ["--contact", "newton"],
               ["--contact", ""], ["--contact", "IPOPT"]]
# The environment of scripts/test_sanitized.sh, for runs that do not set it.
SANITIZER_ENV = {
    "ASAN_OPTIONS": "detect_leaks=1:abort_on_error=1:strict_string_checks=1",
    "LSAN_OPTIONS": "suppressions=%s:print_suppressions=0" % os.path.join(ROOT, "scripts", "sanitizer.supp"),
    "UBSAN_OPTIONS": "print_stacktrace=1:halt_on_error=1",
}
SANITIZER_REPORT = re.compile(
    r"^.*(ERROR: (Address|Leak|UndefinedBehavior|Memory|Thread)Sanitizer|: runtime error: |"
    r"SUMMARY: (Address|Leak|UndefinedBehavior|Memory|Thread)Sanitizer).*$", re.MULTILINE)
SCANNED_OUTPUTS = (".vtu", ".csv", ".json", ".pvd", ".toml")  # the state files are not scanned


# ---------------------------------------------------------------- mutations

def mutate_text(text, rng):
    lines = text.split("\n")
    kind = rng.choice(["value", "value", "value", "type", "delete", "duplicate", "truncate", "garbage", "nest"])
    assignments = [i for i, line in enumerate(lines) if NUMBER.match(line) and not line.lstrip().startswith("#")]
    if kind in ("value", "type") and assignments:
        i = rng.choice(assignments)
        m = NUMBER.match(lines[i])
        new = rng.choice(HOSTILE_NUMBERS if kind == "value" else WRONG_TYPES)
        old = m.group(2)
        # Inside arrays and inline tables replace one number, else the whole value.
        numbers = list(re.finditer(r"-?\d+(\.\d*)?([eE][-+]?\d+)?", old))
        if numbers and (old.startswith("[") or old.startswith("{")):
            n = rng.choice(numbers)
            old = old[:n.start()] + new + old[n.end():]
        else:
            old = new
        lines[i] = m.group(1) + old
        return "\n".join(lines), "%s at line %d" % (kind, i + 1)
    if kind == "delete" and lines:
        i = rng.randrange(len(lines))
        del lines[i]
        return "\n".join(lines), "line %d deleted" % (i + 1)
    if kind == "duplicate" and lines:
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i])
        return "\n".join(lines), "line %d duplicated" % (i + 1)
    if kind == "truncate":
        n = rng.randrange(len(text) + 1)
        return text[:n], "truncated at byte %d" % n
    if kind == "garbage":
        n = rng.randrange(len(text) + 1)
        junk = "".join(chr(rng.randrange(1, 256)) for _ in range(rng.randrange(1, 40)))
        return text[:n] + junk + text[n:], "garbage at byte %d" % n
    depth = rng.choice([2, 50, 1000, 5000])
    return ".".join(["a"] * depth) + ".b = 1\n" + text, "%d nested dotted keys" % depth


def set_override(keys, rng):
    key = rng.choice(keys)
    value = rng.choice(HOSTILE_NUMBERS + WRONG_TYPES)
    return ["--set", "%s=%s" % (key, value)], "--set %s=%s" % (key, value)


def cli_options(rng, default_steps, sanitized):
    """The case's --steps value and further options: for one case in three one or more of --steps,
    --contact, --refine with valid values (--refine 2 with --steps 1), and in one such case in ten
    an invalid value (then the third value, why exit 2 is due, is not empty)."""
    if rng.random() >= 1.0 / 3.0:
        return ["--steps", str(default_steps)], "", ""
    if rng.random() < 0.1:
        bad = list(rng.choice(BAD_OPTIONS))
        steps = [] if bad[0] == "--steps" else ["--steps", str(default_steps)]
        return steps + bad, " ".join(bad), "invalid option"
    chosen = [o for o in ("--steps", "--contact", "--refine") if rng.random() < 0.5]
    if not chosen:
        chosen = [rng.choice(["--steps", "--contact", "--refine"])]
    steps = default_steps
    extra = []
    if "--steps" in chosen:
        steps = rng.choice([1, 2] if sanitized else [1, 2, 3])
    if "--contact" in chosen:
        extra += ["--contact", rng.choice(["penalty", "ipopt"])]
    if "--refine" in chosen:
        refine = rng.choice(["1"] if sanitized else ["1", "2"])
        extra += ["--refine", refine]
        if refine == "2":  # four times the elements: one step keeps the case short
            steps = 1
            chosen.append("--steps")
    what = " ".join((["--steps", str(steps)] if "--steps" in chosen else []) + extra)
    return ["--steps", str(steps)] + extra, what, ""


def scene_keys(roller, work):
    out = run([roller, "scene-keys"], os.path.join(work, "scene-keys.log"), env=sanitizer_env()).check().output()
    keys = []
    for line in out.splitlines()[1:]:
        k = line.split()[0] if line.split() else ""
        if k and "[]" not in k and "." in k:
            keys.append(k)
    return keys


# ---------------------------------------------------------------- running and judging

def sanitizer_env():
    """The sanitizer options that the environment does not set already."""
    return {k: v for k, v in SANITIZER_ENV.items() if k not in os.environ}


def run_case(roller, scene_path, extra, out_dir, timeout):
    """One case's run into out_dir, its output in out_dir.log: a RunResult."""
    return run(roller_command(roller, scene_path, out_dir, "--overwrite", *extra), out_dir + ".log", timeout,
               sanitizer_env())


def sanitizer_report(output):
    """The most telling line of a sanitizer report in the output (SUMMARY, else the first one)."""
    lines = [m.group(0).strip() for m in SANITIZER_REPORT.finditer(output)]
    if not lines:
        return ""
    summary = [line for line in lines if line.startswith("SUMMARY:")]
    line = re.sub(r"^==\d+==", "", (summary or lines)[0])
    return line[:200]


def describe(flagged, out_dir):
    return "; ".join("%s: %s" % (os.path.relpath(p, out_dir), ", ".join(r.messages)) for p, r in flagged)[:400]


@dataclass
class Verdict:
    problem: str                # "" when the case passed
    flagged: list               # (path, FileScan) of the output files that fail it
    scan: FolderScan = None     # the scan of the outputs, when they were scanned


def exit_problem(rc, output, timed_out, expect_exit2="", failed_lines=("error:",)):
    """Why roller's exit code and output fail a case ("" when they are documented): a sanitizer
    report, a hang, a crash, an internal error, an exit code without its message; expect_exit2: why
    the case must end in exit 2 (an invalid option or value), "" when any documented code will do;
    failed_lines: what exit 1's message holds (one of them)."""
    report = sanitizer_report(output)
    if report:
        return "sanitizer report (exit %s): %s" % ("timeout" if timed_out else rc, report)
    if timed_out:
        return "hang (timeout)"
    if rc is None or rc < 0 or rc >= 128:
        return "crash (signal %s)" % (-rc if rc is not None and rc < 0 else rc)
    if "roller: internal error:" in output or "roller: error:" in output:
        tail = output.split("error:", 1)[-1].strip().splitlines()
        return "unexpected exception (exit %d): %s" % (rc, tail[0][:120] if tail else "")
    if rc == 2 and "input error" not in output and "Run with --help" not in output:
        return "exit 2 without an input-error message"
    if rc == 1 and not any(line in output for line in failed_lines):
        return "exit 1 without an error line"
    if rc == 3 and "system error" not in output:
        return "exit 3 without a system-error message"
    if rc not in (0, 1, 2, 3):
        return "undocumented exit code %d" % rc
    if expect_exit2 and rc != 2:
        return "exit %d where exit 2 was due (%s)" % (rc, expect_exit2)
    return ""


def verdict(rc, output, timed_out, out_dir, expect_exit2=""):
    problem = exit_problem(rc, output, timed_out, expect_exit2)
    if problem:
        return Verdict(problem, [])
    scan = scan_outputs(out_dir, endings=SCANNED_OUTPUTS)
    malformed = [f for f in scan.flagged if f[1].finding == Finding.MALFORMED]
    nonfinite = [f for f in scan.flagged if f[1].finding == Finding.NONFINITE]
    if malformed:
        return Verdict("malformed output after exit %d: %s" % (rc, describe(malformed, out_dir)), scan.flagged, scan)
    if nonfinite and rc == 0:
        return Verdict("exit 0 (converged) but nan/inf in an output: %s" % describe(nonfinite, out_dir),
                       scan.flagged, scan)
    if nonfinite:
        return Verdict("nan/inf in an output after exit %d: %s" % (rc, describe(nonfinite, out_dir)),
                       scan.flagged, scan)
    return Verdict("", [], scan)


def save_failure(failures, case, scene_path, cmd, output, problem, what, seed, flagged, out_dir, sanitized):
    d = os.path.join(failures, "%04d" % case)
    os.makedirs(d)
    shutil.copy(scene_path, os.path.join(d, "scene.toml"))
    # The command as run, on the saved scene and into OUT/failures/<n>/out.
    cmd = [os.path.join(d, "scene.toml") if a == scene_path else os.path.join(d, "out") if a == out_dir else a
           for a in cmd]
    env = [k + "=" + os.environ.get(k, v) for k, v in sorted(SANITIZER_ENV.items())] if sanitized else []
    with open(os.path.join(d, "command.txt"), "w") as f:
        f.write("# %s: %s (from problems/%s.toml)\n%s\n" % (problem, what, seed, shlex.join(env + cmd)))
    with open(os.path.join(d, "output.txt"), "w") as f:
        f.write(output)
    for path, _ in flagged:
        target = os.path.join(d, "outputs", os.path.relpath(path, out_dir))
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy(path, target)
    return d


def scan_command(paths):
    """--scan: print what the scanner sees in the given files or folders."""
    n_bad = 0
    files = []
    for p in paths:
        files += files_under(p) if os.path.isdir(p) else [p]
    for path in files:
        if not path.endswith(SCANNED_OUTPUTS):
            print("%s: not scanned" % path)
            continue
        result = scan_file(path)
        if path.endswith(".vtu") and result.finding != Finding.MALFORMED:
            arrays = decode_vtu(path)
            print("%s: %d arrays" % (path, len(arrays)))
            for section, name, values in arrays:
                print("    %-9s %-24s %-8s %d x %d" % (section, name, values.dtype.name, *values.shape))
        elif result.finding == Finding.CLEAN:
            print("%s: clean" % path)
        if result.finding != Finding.CLEAN:
            n_bad += 1
            print("%s: %s: %s" % (path, "NAN/INF" if result.finding == Finding.NONFINITE else "MALFORMED",
                                  "; ".join(result.messages)))
    return 1 if n_bad else 0


def main(argv=None):
    ap = parser("fuzz-scenes", __doc__)
    ap.add_argument("--cases", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--roller", default=DEFAULT_ROLLER)
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "fuzz"))
    ap.add_argument("--timeout", type=float, default=30.0)
    ap.add_argument("--steps", type=int, default=None, help="steps per run (default 2, with --sanitized 1)")
    ap.add_argument("--sanitized", action="store_true",
                    help="ROLLER is a sanitizer build: smaller scenes, --steps 1, no --refine 2")
    ap.add_argument("--scan", nargs="+", metavar="PATH", help="only scan these output files or folders")
    args = ap.parse_args(argv)
    if args.scan:
        return scan_command(args.scan)
    wrong = self_check()
    if wrong:
        print("fuzz: the output scanner misses planted values:\n    " + "\n    ".join(wrong))
        return 1
    scanned = {"files": 0, "vtu": 0, "arrays": 0}  # what the scan of the runs' outputs looked at
    steps = args.steps if args.steps is not None else (1 if args.sanitized else 2)
    seeds = SMALL_SEEDS if args.sanitized else SEEDS
    rng = random.Random(args.seed)
    work = os.path.join(args.out, "work")
    failures = os.path.join(args.out, "failures")
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(work)
    keys = scene_keys(args.roller, work)
    counts = {}
    n_failed = 0
    t0 = time.monotonic()
    for case in range(1, args.cases + 1):
        share = rng.random()
        seed = rng.choice((SMALL_PASS_SEEDS if args.sanitized else PASS_SEEDS) if share < PASS_SHARE else seeds)
        with open(os.path.join(PROBLEMS, seed + ".toml")) as f:
            text = f.read()
        extra, what, due = [], "", ""
        if share < PASS_SHARE:  # stationary passes: a pass's steps are the scene's, no --steps
            if rng.random() < 0.3:
                text, what = mutate_text(text, rng)
            options, options_what, due = pass_case(rng, args.sanitized)
        else:
            if share < PASS_SHARE + LAYER_SHARE:
                text, extra, what = layer_case(text, rng, HOSTILE_NUMBERS + WRONG_TYPES)
            elif share < PASS_SHARE + LAYER_SHARE + TWICE_SHARE:
                extra, what, due = twice_case(rng)
            elif rng.random() < 0.3:
                extra, what = set_override(keys, rng)
            else:
                text, what = mutate_text(text, rng)
            options, options_what, bad_option = cli_options(rng, steps, args.sanitized)
            due = due or bad_option
        if options_what:
            what += ", " + options_what
        scene_path = os.path.join(work, "case.toml")
        with open(scene_path, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(text)
        out_dir = os.path.join(work, "out")
        result = run_case(args.roller, scene_path, options + extra, out_dir, args.timeout)
        output = result.output()
        judged = verdict(result.exit_code, output, result.timed_out, out_dir, due)
        if judged.scan:
            scanned["files"] += judged.scan.files
            scanned["vtu"] += judged.scan.vtu_files
            scanned["arrays"] += judged.scan.arrays
        key = "timeout" if result.timed_out else str(result.exit_code)
        counts[key] = counts.get(key, 0) + 1
        if judged.problem:
            n_failed += 1
            d = save_failure(failures, case, scene_path, result.command, output, judged.problem, what, seed,
                             judged.flagged, out_dir, args.sanitized)
            print("case %4d FAILED %s: %s (problems/%s.toml) -> %s" % (case, judged.problem, what, seed, d),
                  flush=True)
        shutil.rmtree(out_dir, ignore_errors=True)
    print("fuzz: %d cases in %.0f s (seed %d%s), exit codes %s; %d output files scanned (%d VTU, %d arrays "
          "decoded); %d failed" % (
              args.cases, time.monotonic() - t0, args.seed, ", sanitized" if args.sanitized else "",
              ", ".join("%s: %d" % kv for kv in sorted(counts.items())), scanned["files"], scanned["vtu"],
              scanned["arrays"], n_failed))
    return 1 if n_failed else 0
