"""Fuzzer of `roller shakedown-limit SCENE` (docs/model.md, "Melan's bound"; docs/stability.md,
"Hostile input"): its options and its output files' paths.

usage: ./rollerpy fuzz-shakedown-limit [--cases 40] [--seed 1] [--roller ./build/roller]
                                      [--out out/fuzz-shakedown-limit] [--timeout 60] [--sanitized]

Each case takes a scene with a rolling segment (case_hardened: a yield profile; the layered
shakedown_case_hardened; shakedown_p45 in the release build) and runs `roller shakedown-limit` with
some of the options below; one thing at most is hostile (none in a case in four): the scene
mutated as fuzz-scenes mutates (fuzz_scenes.mutate_text), or one option's value or target among
  --traction  a valid q/p (0, 0.2, 10, 1e-308) or a hostile one: nan, inf, -inf, -1, 1e308,
              10.000001, "x", "" (exit 2 is due);
  --refine    1 (2 in the release build) or an invalid value (0, 65, nan, -1, x: exit 2 is due);
  --set       a valid value, a random key (`roller scene-keys`) with a hostile value, or one key
              given twice with nan or inf among its values (exit 2 is due);
  --csv/--json  a path of one of these kinds: a new file, an existing regular file, a file in a
              folder that does not exist, '' (empty), a folder, a FIFO (os.mkfifo in the case's
              folder), a symbolic link to another file, a null device node of the case's folder
              (mknod c 1 3; a FIFO in its place where the fuzzer may not make device nodes). The
              machine's own /dev/null is never a target: a regression would replace it.
A case passes when roller ends as fuzz-scenes judges (fuzz_scenes.exit_problem: documented exit
code with its message, no crash, hang or sanitizer report; exit 1's message is "shakedown-limit
failed"), exit 2 where it is due: an empty path or an existing target that is not a regular file
(a folder, a FIFO, a device, a symbolic link: lstat) must be refused; no such target is replaced
or written through (a FIFO is still a FIFO, a link still the same link, the file it points to
unchanged, a device still a device); on exit 0 every requested regular file exists; the CSV
holds no nan and no inf but in its p0/k columns (an unlimited row), the JSON no nan, inf or null
but a bound's load factor and p0/k when no depth limits it (the bound has no depth); roller's
printed result holds no nan.
Reproducers in OUT/failures/<case>/. Exit code 0 when every case passed, 1 otherwise.

--sanitized: ROLLER is a sanitizer build: case_hardened and shakedown_case_hardened only, no
--refine 2, the sanitizer options of fuzz-scenes. CTest runs 30 cases (label fuzz) and, in the
sanitizer build, 6 (label fast).
"""
import csv
import json
import math
import os
import stat

from ..paths import PROBLEMS
from ..runner import run
from ..scan import NONFINITE_TOKEN
from .fuzz_cases import Campaign, options
from .fuzz_scenes import SANITIZER_ENV, exit_problem, mutate_text, sanitizer_env, scene_keys, set_override
from .fuzz_shares import twice_case

SEEDS = ["case_hardened", "shakedown_case_hardened", "case_hardened", "shakedown_p45"]
SMALL_SEEDS = ["case_hardened", "shakedown_case_hardened"]
TRACTIONS = ["0", "0.2", "10", "1e-308", "-0.0"]
BAD_TRACTIONS = ["nan", "NaN", "inf", "-inf", "-1", "1e308", "10.000001", "x", ""]
BAD_REFINES = ["0", "65", "nan", "-1", "x"]
GOOD_SETS = [["--set", "contact.friction=0.2"], ["--set", "material.yield_stress=900.0"],
             ["--set", "material.nu=0.25"], ["--set", "contact.friction=0.0"]]
TARGETS = ["new", "new", "existing", "missing_folder", "empty", "folder", "fifo", "symlink", "device"]
REFUSED = {"empty", "folder", "fifo", "symlink", "device"}  # exit 2 is due
P0K_COLUMNS = {"first_yield_p0_over_k", "elastic_p0_over_k", "kinematic_p0_over_k"}  # "inf": an unlimited row
UNLIMITED_KEYS = {"load_factor", "p0_over_k"}  # null in a bound without a depth: no depth limits it


def make_target(kind, folder, ending, flag):
    """The path of one output option's target, made in `folder` as its kind asks."""
    name = flag.strip("-")
    path = os.path.join(folder, "%s_%s%s" % (name, kind, ending))
    if kind == "empty":
        return kind, ""
    if kind == "missing_folder":
        return kind, os.path.join(folder, "no", "such", "folder", "limit" + ending)
    if kind == "existing":
        with open(path, "w") as f:
            f.write("an older file\n")
    elif kind == "folder":
        os.mkdir(path)
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "device":
        try:
            os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(1, 3))
        except PermissionError:  # not root: a FIFO is refused alike
            os.mkfifo(path)
            kind = "fifo"
    elif kind == "symlink":
        with open(path + ".linked", "w") as f:
            f.write("the file a link points to: %s\n" % path)
        os.symlink(os.path.basename(path) + ".linked", path)
    return kind, path


def setup_line(kind, path):
    """The shell line that makes a target of this kind again (for the reproducer)."""
    return {"existing": "echo 'an older file' > %s" % path, "folder": "rm -rf %s; mkdir %s" % (path, path),
            "fifo": "rm -rf %s; mkfifo %s" % (path, path), "device": "rm -rf %s; mknod %s c 1 3" % (path, path),
            "symlink": "rm -rf %s; echo 'the file a link points to: %s' > %s.linked; ln -s %s.linked %s" % (
                path, path, path, os.path.basename(path), path)}.get(kind, "")


def target_problem(kind, path):
    """Why a refused target is no longer what it was ("" when it is)."""
    try:
        mode = os.lstat(path).st_mode
    except FileNotFoundError:
        return "%s target %s removed" % (kind, path) if kind in ("folder", "fifo", "symlink", "device") else ""
    if kind == "folder" and not stat.S_ISDIR(mode):
        return "the folder %s replaced" % path
    if kind == "fifo" and not stat.S_ISFIFO(mode):
        return "the FIFO %s replaced" % path
    if kind == "device" and not stat.S_ISCHR(mode):
        return "the device node %s replaced" % path
    if kind == "symlink":
        if not stat.S_ISLNK(mode) or os.readlink(path) != os.path.basename(path) + ".linked":
            return "the symbolic link %s replaced" % path
        with open(path + ".linked") as f:
            if f.read() != "the file a link points to: %s\n" % path:
                return "written through the symbolic link %s" % path
    return ""


def csv_problem(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for number, row in enumerate(rows, 2):
        for column, cell in row.items():
            c = (cell or "").strip()
            if not c or (c == "inf" and column in P0K_COLUMNS):
                continue
            try:
                value = float(c)
            except ValueError:
                return "%s line %d: %s = %r, not a number" % (os.path.basename(path), number, column, c)
            if not math.isfinite(value):
                return "%s line %d: %s = %s" % (os.path.basename(path), number, column, c)
    return ""


def json_problem(path):
    def walk(value, where, unlimited):
        if isinstance(value, dict):
            free = "depth" not in value
            for k, v in value.items():
                found = walk(v, where + "." + k, free and k in UNLIMITED_KEYS)
                if found:
                    return found
        elif value is None and not unlimited:
            return "%s is null" % where
        elif isinstance(value, float) and not math.isfinite(value):
            return "%s = %s" % (where, value)
        return ""
    try:
        with open(path) as f:
            doc = json.load(f)
    except ValueError as e:
        return "%s does not parse: %s" % (os.path.basename(path), e)
    found = walk(doc, "", False)
    if found and doc.get("elastic", {}).get("depth") is None and found == ".first_yield_p0_over_k is null":
        return ""  # a strip that never yields
    return "%s: %s" % (os.path.basename(path), found) if found else ""


def judge(rc, output, timed_out, due, targets):
    """The case's problem ("" when it passed); targets: (flag, kind, path)."""
    problem = exit_problem(rc, output, timed_out, due, failed_lines=("shakedown-limit failed", "error:"))
    broken = [p for p in (target_problem(kind, path) for _, kind, path in targets if kind in REFUSED) if p]
    if broken:
        return "; ".join(broken) + (" (%s)" % problem if problem else " (exit %s)" % rc)
    if problem:
        return problem
    if rc == 0 and any(NONFINITE_TOKEN.fullmatch(t) and t.lower().endswith("nan") for t in output.split()):
        return "nan in the printed result"
    for flag, kind, path in targets:
        if kind in REFUSED:
            continue
        if rc == 0 and not os.path.isfile(path):
            return "exit 0 but no %s file %s" % (flag, path)
        if os.path.isfile(path) and (kind != "existing" or rc == 0):
            found = (csv_problem if flag == "--csv" else json_problem)(path)
            if found:
                return "non-finite value after exit %d: %s" % (rc, found)
    return ""


def main(argv=None):
    args = options("fuzz-shakedown-limit", __doc__, 40, 60.0).parse_args(argv)
    fuzz = Campaign("fuzz-shakedown-limit", args)
    rng = fuzz.rng
    keys = scene_keys(args.roller, fuzz.work)
    for case in range(1, args.cases + 1):
        folder = fuzz.case_dir(case)
        seed = rng.choice(SMALL_SEEDS if args.sanitized else SEEDS)
        with open(os.path.join(PROBLEMS, seed + ".toml")) as f:
            text = f.read()
        # One hostile thing a case at most (none in one case in four), the rest valid or absent.
        hostile = rng.choice(["", "", "", "mutate", "traction", "traction", "refine", "set", "twice", "--csv",
                              "--json", "--csv", "--json"])
        what = ["problems/%s.toml" % seed]
        if hostile == "mutate":
            text, mutation = mutate_text(text, rng)
            what.append(mutation)
        scene = os.path.join(folder, "scene.toml")
        with open(scene, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(text)
        words, dues = [], []
        if hostile == "traction" or rng.random() < 0.4:
            value = rng.choice(BAD_TRACTIONS if hostile == "traction" else TRACTIONS)
            words += ["--traction", value]
            dues += ["--traction %r" % value] if hostile == "traction" else []
        if hostile == "refine" or rng.random() < 0.2:
            value = rng.choice(BAD_REFINES if hostile == "refine" else (["1"] if args.sanitized else ["1", "2"]))
            words += ["--refine", value]
            dues += ["--refine %r" % value] if hostile == "refine" else []
        if hostile == "set":
            words += set_override(keys, rng)[0]
        elif hostile == "twice":
            twice, _, due = twice_case(rng)
            words += twice
            dues.append(due)
        elif rng.random() < 0.3:
            words += rng.choice(GOOD_SETS)
        targets = []
        for flag, ending in (("--csv", ".csv"), ("--json", ".json")):
            if hostile == flag or rng.random() < 0.5:
                kinds = [k for k in TARGETS if (k in REFUSED) == (hostile == flag)]
                kind, path = make_target(rng.choice(kinds), folder, ending, flag)
                targets.append((flag, kind, path))
                words += [flag, path]
                dues += ["%s to %s %r" % (flag, kind, path)] if kind in REFUSED else []
        command = [args.roller, "shakedown-limit", scene] + words
        result = run(command, os.path.join(folder, "output.txt"), args.timeout, sanitizer_env())
        output = result.output()
        problem = judge(result.exit_code, output, result.timed_out, "; ".join(dues), targets)
        outcome = "timeout" if result.timed_out else str(result.exit_code)
        setup = [setup_line(k, p) for _, k, p in targets]
        fuzz.record(case, outcome, problem, " ".join(what + words[:40]), command, output, [scene],
                    SANITIZER_ENV if args.sanitized else None, [line for line in setup if line])
    return fuzz.finish()
