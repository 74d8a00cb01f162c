"""Fuzzer of study files (`rollerpy study`, docs/studies.md; docs/stability.md, "Hostile input").

usage: ./rollerpy fuzz-study [--cases 30] [--seed 1] [--roller ./build/roller]
                            [--out out/fuzz-study] [--timeout 60] [--sanitized]

Each case writes a small study of problems/block_compression.toml (2 steps, 1 or 2 points) and
changes it: a hostile value in [grid] (nan, inf, empty lists, ranges with a zero, tiny or
non-finite step, a count of 0, -1, 1.5, 2**70), in [[point]] blocks (different keys, empty
blocks), in [set] (wrong types, a 1000-level inline table), in `backends`, `timeout`, `scene`,
`title`, an unknown key, or a `collect` entry that points outside the point's folder (an absolute
path, '../', '..\\', a NUL byte) or is malformed; or the file mutated as fuzz-scenes mutates scenes
(fuzz_scenes.mutate_text). Now and then a symbolic link to a file outside is planted in a point's
folder before the study and collected. The study runs with --serial, or on a LocalCluster of one
worker (--jobs 1) one case in five, now and then with an invalid --jobs (exit 2 is due).
A sentinel, a CSV file with a number unique to the case, lies outside every point's folder at each
place such an entry names (the case's folder, OUT, OUT/points). A case passes when the study ends
with a documented exit code (0; 2 with a "study:" line), prints no Python traceback, no value of
the sentinel appears in study.csv, the collected columns of study.csv hold no nan or inf and the
points' output files none either (point.json, which repeats the study's values, aside), and no
point's run.log holds a sanitizer report. Reproducers: OUT/failures/<case>/ (command.txt,
output.txt, study.toml; the case's folder OUT/work/<case>/ is kept). Exit code 0 when every case
passed, 1 otherwise.

--sanitized: ROLLER is a sanitizer build: --serial and one point only; the sanitizer options of
fuzz-scenes are set. CTest runs 20 cases (label fuzz) and, in the sanitizer build, 5 (label fast).
"""
import csv
import math
import os
import sys

from ..paths import PROBLEMS, ROOT
from ..runner import run
from ..scan import scan_outputs
from .fuzz_cases import Campaign, options
from .fuzz_scenes import SANITIZER_ENV, SCANNED_OUTPUTS, mutate_text, sanitizer_env, sanitizer_report

BLOCK = os.path.join(PROBLEMS, "block_compression.toml")
BASE = '''title = "fuzz-study case"
scene = %s
timeout = %s
collect = [%s]

[set]
"steps.count" = 2

%s
'''
GRIDS = ['[grid]\n"material.E" = [2.1e5]', '[grid]\n"material.E" = [2.1e5, 1.9e5]',
         '[[point]]\n"material.nu" = 0.3', '[[point]]\n"material.nu" = 0.3\n[[point]]\n"material.nu" = 0.25']
HOSTILE_GRIDS = [
    '[grid]\n"material.E" = [nan]', '[grid]\n"material.E" = [inf, -inf]', '[grid]\n"material.E" = []',
    '[grid]\n"material.E" = { start = 1e5, stop = nan, count = 2 }',
    '[grid]\n"material.E" = { start = 1e5, stop = 2e5, step = 0.0 }',
    '[grid]\n"material.E" = { start = 1e5, stop = 2e5, step = 1e-300 }',
    '[grid]\n"material.E" = { start = 1e5, stop = 2e5, step = inf }',
    '[grid]\n"material.E" = { start = 1e5, stop = 2e5, count = %s }',
    '[grid]\n"material.E" = { start = 1e5, stop = 2e5 }', '[grid]\n"material.E" = 2.1e5',
    '[grid]\n"" = [1]', '[grid]\n"material.E=1 --steps" = [2.1e5]', '[grid]\n"steps.count" = [2]',
    '[grid]\n"material.E" = [2.1e5, "x", true, [1], {}]', '[grid]\n"material.E" = [1e308]',
    '[[point]]\n"material.nu" = 0.3\n[[point]]\n"material.E" = 2e5', '[[point]]', '[[point]]\n"material.nu" = nan',
    '[[point]]\n"material.nu" = 0.3\n[grid]\n"material.E" = [2e5]', 'point = 5', 'grid = []',
    '[grid]\n"material.E" = [%s]']
COUNTS = ["0", "-1", "1.5", '"2"', "nan", "1180591620717411303424", "1e20"]
SETS = ['"material.E" = nan', '"material.E" = "x"', '"steps.count" = 2.5', '"material" = 5',
        '"material.E" = { a = 1 }', '"mesh.nx" = 1180591620717411303424', '"" = 1', '"material.E" = []',
        '"x" = ' + "{ a = " * 1000 + "1" + " }" * 1000, '"x" = ' + "[" * 1000 + "]" * 1000]
BACKENDS = ['backends = []', 'backends = ["x"]', 'backends = "ipopt"', 'backends = [1]',
            'backends = ["ipopt", "ipopt"]', 'backends = ["penalty", "ipopt"]', 'backends = [nan]']
TIMEOUTS = ["0", "-1", "nan", "inf", "1e8", '"x"', "true", "1e-9", "[]"]
SCENES = ['""', '"/dev/null"', '"missing.toml"', '"."', '"study.toml"', "5", '"%s\\u0000x"' % BLOCK,
          '"' + "x" * 5000 + '"']
TOPS = ['title = 5', 'title = "%s"' % ("t" * 100000), 'what = 1', 'title = "\\u0000"']
OUTSIDE = ["../secret.csv:v", "../../secret.csv:v", "../../../secret.csv:v", "ABS:v", "ABS:v:max",
           "..\\\\secret.csv:v", "sub/../../secret.csv:v", "./../secret.csv:v", "..//secret.csv:v"]
BAD_COLLECT = ['""', '"status"', '":"', '"a.csv:"', '"solver.csv:iterations:nope"', '"x\\u0000.csv:v"',
               '"solver.csv:iterations:step=99999999999999999999"', '"' + "a" * 10000 + '"', "5", '"a..b"',
               '"solver.csv:iterations:step=-1"', '"summary.json:x"']
GOOD_COLLECT = ['"converged"', '"iterations_total"', '"solver.csv:iterations"', '"solver.csv:residual:max"']


def plant_sentinels(folder, out, value):
    """The sentinel CSV (column v) at every place an entry that escapes a point's folder names."""
    for d in (folder, out, os.path.join(out, "points")):
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "secret.csv"), "w") as f:
            f.write("v\n%s\n" % value)


def study_text(rng, folder, sanitized):
    """The case's study file and what it changed; the third value is true when a point's folder
    gets a planted link (link.csv, to the case's sentinel)."""
    collect = rng.sample(GOOD_COLLECT, rng.randrange(0, 3))
    grid = rng.choice(GRIDS[:1] + GRIDS[2:3] if sanitized else GRIDS)
    scene, timeout, extra, what, link = '"%s"' % BLOCK, "60", [], [], False
    kind = rng.choice(["collect", "collect", "grid", "grid", "set", "backends", "timeout", "scene", "top",
                       "link", "text"])
    if kind == "collect":
        if rng.random() < 0.6:
            entry = '"%s"' % rng.choice(OUTSIDE).replace("ABS", os.path.join(folder, "secret.csv"))
        else:
            entry = rng.choice(BAD_COLLECT)
        collect.insert(rng.randrange(len(collect) + 1), entry)
        what.append("collect %s" % entry[:80])
    elif kind == "link":
        collect.append('"link.csv:v"')
        link = True
        what.append("link.csv in the point's folder -> the sentinel outside, collected")
    elif kind == "grid":
        grid = rng.choice(HOSTILE_GRIDS).replace("%s", rng.choice(COUNTS))
        what.append(grid.replace("\n", " ")[:120])
    elif kind == "set":
        value = rng.choice(SETS)
        what.append("[set] %s" % value[:80])
    elif kind == "backends":
        extra.append(rng.choice(BACKENDS))
        what.append(extra[-1])
    elif kind == "timeout":
        timeout = rng.choice(TIMEOUTS)
        what.append("timeout = %s" % timeout)
    elif kind == "scene":
        scene = rng.choice(SCENES)
        what.append("scene = %s" % scene[:80])
    elif kind == "top":
        extra.append(rng.choice(TOPS))
        what.append(extra[-1][:80])
    text = BASE % (scene, timeout, ", ".join(collect), grid)
    if kind == "set":
        text = text.replace('"steps.count" = 2\n', '"steps.count" = 2\n%s\n' % value)
    text = "\n".join(extra) + "\n" + text
    if kind == "text":
        text, mutation = mutate_text(text, rng)
        what.append(mutation)
    return text, "; ".join(what), link


def collected_problem(csv_path, collect_names, sentinel):
    with open(csv_path, errors="replace") as f:
        text = f.read()
    if sentinel in text:
        return "study.csv holds the sentinel %s: a collect entry read outside the point's folder" % sentinel
    for row in csv.DictReader(text.splitlines()):
        for name in collect_names:
            cell = (row.get(name) or "").strip()
            try:
                value = float(cell)
            except ValueError:
                continue
            if not math.isfinite(value):
                return "study.csv: collected %s = %s" % (name, cell)
    return ""


def judge(rc, output, timed_out, due, out, sentinel):
    if timed_out:
        return "hang (timeout)"
    if "Traceback (most recent call last)" in output:
        tail = [line for line in output.splitlines() if line.strip()]
        return "Python traceback (exit %s): %s" % (rc, tail[-1][:200] if tail else "")
    if rc is None or rc < 0 or rc >= 128:
        return "crash (signal %s)" % (-rc if rc is not None and rc < 0 else rc)
    if rc not in (0, 2):
        return "undocumented exit code %d" % rc
    if rc == 2 and "study:" not in output and "usage:" not in output:
        return "exit 2 without a study: line"
    if due and rc != 2:
        return "exit %d where exit 2 was due (%s)" % (rc, due)
    csv_path = os.path.join(out, "study.csv")
    if os.path.exists(csv_path):
        found = collected_problem(csv_path, [c.strip('"') for c in GOOD_COLLECT] + ["wall_s"], sentinel)
        if found:
            return found
    elif rc == 0:
        return "exit 0 without study.csv"
    points = os.path.join(out, "points")
    for name in sorted(os.listdir(points)) if os.path.isdir(points) else []:
        log = os.path.join(points, name, "run.log")
        report = sanitizer_report(open(log, errors="replace").read()) if os.path.isfile(log) else ""
        if report:
            return "sanitizer report in %s/run.log: %s" % (name, report)
    scan = scan_outputs(points, endings=SCANNED_OUTPUTS) if os.path.isdir(points) else None
    flagged = [p for p, _ in scan.flagged if os.path.basename(p) not in ("point.json", "secret.csv")] if scan else []
    if flagged:
        return "nan/inf in a point's output: %s" % os.path.relpath(flagged[0], out)
    return ""


def main(argv=None):
    args = options("fuzz-study", __doc__, 30, 120.0).parse_args(argv)
    fuzz = Campaign("fuzz-study", args)
    rng = fuzz.rng
    launcher = os.path.join(ROOT, "rollerpy")
    for case in range(1, args.cases + 1):
        folder = fuzz.case_dir(case)
        out = os.path.join(folder, "out")
        sentinel = "%d.%03d" % (73310000 + case, rng.randrange(1000))
        plant_sentinels(folder, out, sentinel)
        text, what, link = study_text(rng, folder, args.sanitized)
        study = os.path.join(folder, "study.toml")
        with open(study, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(text)
        setup = []
        if link:
            for name in ("p000", "p001", "p000_ipopt"):
                os.makedirs(os.path.join(out, "points", name))
                os.symlink(os.path.join(folder, "secret.csv"), os.path.join(out, "points", name, "link.csv"))
                setup.append("mkdir -p %s/points/%s; ln -sf %s/secret.csv %s/points/%s/link.csv" % (
                    out, name, folder, out, name))
        engine, due = ["--serial"], ""
        if not args.sanitized and rng.random() < 0.2:
            engine = ["--jobs", "1"]
        if rng.random() < 0.05:
            engine = ["--jobs", rng.choice(["0", "-1"])]
            due = "--jobs %s" % engine[1]
        command = [launcher, "study", study, "--out", out, "--roller", os.path.abspath(args.roller),
                   "--quiet"] + engine
        result = run(command, os.path.join(folder, "output.txt"), args.timeout, sanitizer_env())
        output = result.output()
        problem = judge(result.exit_code, output, result.timed_out, due, out, sentinel)
        fuzz.record(case, "timeout" if result.timed_out else str(result.exit_code), problem,
                    "%s%s" % (what, " " + " ".join(engine)), command, output, [study],
                    SANITIZER_ENV if args.sanitized else None, setup)
    return fuzz.finish()


if __name__ == "__main__":
    sys.exit(main())
