"""Fuzzer of the Python entry rollerpy.run (docs/python.md, "roller in process"; docs/stability.md,
"Hostile input"): dict scenes, other sources and the keyword arguments.

usage: ./rollerpy fuzz-python [--cases 60] [--seed 1] [--out out/fuzz-python] [--timeout 60]

Each case is a Python script, OUT/work/<case>/case.py, run by /usr/bin/python3 in a process of its
own (PYTHONPATH: this package's python/ folder, where scripts/build.sh puts rollerpy._roller), so
that a crash is seen and judged. The script reads a shipped scene with tomllib and changes it:
  - a value replaced by a hostile one: nan, inf, 1e308, -1, 2**70, -2**70, 2**64, None, bytes, a
    string, a list, a dict, a complex number, a Decimal, an object, numpy's nan;
  - a number given as numpy's type of the same value (int64, int32, uint8, float64, float32, bool_):
    the call must then go as with the plain value (a result where the plain call returns one);
  - a dict or a list nested 300, 1000 or 100,000 levels deep, as a value, a new table or a --set value;
  - a table replaced by another type, a key deleted, a key that is not a string;
  - another source: None, a number, bytes, '', a folder, a missing file, a list, a pathlib.Path;
  - the keywords: `set` (None, a string, numpy values, unknown keys, path segments out of range,
    huge indices), `out` ('', a number, bytes, a regular file, a FIFO of the case's folder, a new
    folder), `overwrite` and `verbose` (non-bools), `progress` (not callable, the wrong arity,
    raising, raising KeyboardInterrupt);
  - two threads calling rollerpy.run at once in the process (each must return or raise a
    documented exception; no crash).
A case passes when every call returns a RunResult whose arrays (tables, fields, mesh) hold no nan
or inf, with the output folder (out=) clean as fuzz-scenes scans it, or raises a documented
exception: rollerpy.InputError (a ValueError), rollerpy.ResourceError, rollerpy.RunInterrupted
after a KeyboardInterrupt in the progress callback, or the callback's own exception raised again
(a TypeError of a callback of the wrong arity included). Anything else fails it: another exception
(a bare TypeError, RuntimeError, "Unable to cast", RecursionError), a crash (signal), a hang (the
timeout), a script that prints no verdict. Reproducers: OUT/failures/<case>/ (command.txt,
output.txt, case.py). Exit code 0 when every case passed, 1 otherwise.

The native module is not built in the sanitizer build (Python would need ASan preloaded), so
--sanitized skips the fuzzer (exit 0, a line says so) when rollerpy._roller does not import; CTest
runs 40 cases (label fuzz) in the release build only.
"""
import os
import subprocess
import sys

from ..paths import PROBLEMS, ROOT
from ..runner import run
from .fuzz_cases import Campaign, options

PYTHON = "/usr/bin/python3"
SCENES = ["block_compression", "hertz", "cattaneo"]
HOSTILE = ['float("nan")', 'float("inf")', '-float("inf")', "1e308", "-1", "0", "2**70", "-2**70", "2**64",
           "2**63", "None", 'b"x"', '"x"', '""', "[]", "{}", "[1, 2]", '{"value": 1}', "1j",
           'decimal.Decimal("1.5")', "object()", 'np.float64("nan")', "np.array([1.0, 2.0])", "True"]
NUMPY_INT = ["np.int64", "np.int32", "np.uint8", "np.int16"]
NUMPY_FLOAT = ["np.float64", "np.float32"]
SOURCES = ["None", "5", 'b"FILE"', '""', "WORK", 'os.path.join(WORK, "missing.toml")', "[]", 'pathlib.Path("FILE")',
           'os.path.join(WORK, "fifo")', '"FILE\\0x"', "{}"]
SETS = ['"steps.count=2"', '{"steps.count": np.int64(2)}', '{"steps.count": 2.0}', '{"no.such_key": 1}',
        '{1: 2}', '{"": 1}', '{"material.E": float("nan")}', '{"roller.path[99].fy": 1.0}',
        '{"roller.path[-1].fy": 1.0}', '{"roller.path[99999999999999999999].fy": 1.0}', '[("steps.count", 2)]',
        '{"material": {"E": 2e5}}', '{"material.E": np.float32(2e5)}', '{"material.E": None}', "{None: None}",
        '{"steps.count": 2**70}', '{"material.E": nest(1000)}', '{"material.E": b"1"}']
KEYWORDS = {
    "out": ['""', "5", 'os.fsencode(os.path.join(WORK, "o"))', 'os.path.join(WORK, "file.txt")',
            'os.path.join(WORK, "fifo")', 'os.path.join(WORK, "new", "out")', 'pathlib.Path(WORK) / "out"'],
    "overwrite": ['"yes"', "None", "1", "np.bool_(True)", "2.5"],
    "verbose": ['"no"', "None", "2", "np.bool_(False)"],
    "progress": ["5", '"print"', "lambda: None", "stop", "interrupt", "lambda row: float(\"nan\")"],
}

# The helpers a case script imports: run one call and print its verdict line.
PRELUDE = '''\
import copy, decimal, os, pathlib, sys, threading, tomllib
import numpy as np
import rollerpy
from rollerpy.validation.fuzz_python import call, nest, nest_list, stop, interrupt
WORK = os.path.dirname(os.path.abspath(__file__))
'''


class ProgressStop(Exception):
    """What the `stop` progress callback raises: rollerpy.run must raise it again."""


def stop(row):
    raise ProgressStop("stopped by the progress callback at step %s" % row.get("step"))


def interrupt(row):
    raise KeyboardInterrupt


def nest(depth, leaf=1.0):
    """A dict nested `depth` levels deep, built without recursion."""
    value = leaf
    for _ in range(depth):
        value = {"a": value}
    return value


def nest_list(depth, leaf=1.0):
    value = leaf
    for _ in range(depth):
        value = [value]
    return value


def nonfinite_in(result):
    """Where a RunResult holds nan or inf ("" when nowhere)."""
    import numpy as np
    arrays = [("mesh.points", result.mesh.points)]
    arrays += [("%s.%s" % (t, c), v) for t, cols in result.tables.items() for c, v in cols.items()]
    for f in result.fields:
        arrays += [("step %d %s" % (f.step, n), v) for n, v in list(f.point_data.items()) + list(f.cell_data.items())]
    for name, values in arrays:
        values = np.asarray(values)
        if values.dtype.kind == "f" and not np.all(np.isfinite(values)):
            return name
    return ""


def call(thunk, like=None, allowed=(), out=None):
    """Runs thunk (a call of rollerpy.run) and prints its verdict line: "VERDICT pass ..." or
    "VERDICT fail ...". allowed: the names of exception types documented for this call besides
    InputError and ResourceError; like: the same call with plain Python values instead of numpy's:
    when it returns a result, thunk must too."""
    import rollerpy
    from ..scan import scan_outputs
    from .fuzz_scenes import SCANNED_OUTPUTS
    expect_result = False
    if like is not None:
        try:
            like()
            expect_result = True
        except (rollerpy.InputError, rollerpy.ResourceError):
            pass
    try:
        result = thunk()
    except (rollerpy.InputError, rollerpy.ResourceError) as e:
        name = type(e).__name__
        verdict = "fail %s where a result was due: %s" % (name, e) if expect_result else "pass %s" % name
    except BaseException as e:  # judged, whatever it is: a KeyboardInterrupt from a callback too
        name = type(e).__name__
        if name in allowed:
            verdict = "pass %s" % name
        else:
            verdict = "fail undocumented exception %s: %s" % (name, str(e).replace("\n", " ")[:200])
    else:
        found = nonfinite_in(result)
        out = os.fsdecode(out) if isinstance(out, (str, bytes, os.PathLike)) else ""
        scan = scan_outputs(out, endings=SCANNED_OUTPUTS) if out and os.path.isdir(out) else None
        if found:
            verdict = "fail nan/inf in the result (%s, status %s)" % (found, result.status)
        elif scan and scan.flagged:
            verdict = "fail nan/inf in the output folder: %s" % scan.problems(out)[0]
        else:
            verdict = "pass result %s" % result.status
    print("VERDICT " + verdict, flush=True)


def leaves(table, path=""):
    """(the place as Python subscripts, value) of every value of a scene that is not a table
    (numbers, strings, bools, arrays), arrays of tables walked into; and of every table."""
    values, tables = [], []
    for k, v in table.items():
        place = "%s[%r]" % (path, k)
        inner = [(place, v)] if isinstance(v, dict) else \
            [("%s[%d]" % (place, i), x) for i, x in enumerate(v)] if isinstance(v, list) and v and all(
                isinstance(x, dict) for x in v) else []
        for where, t in inner:
            tables.append(where)
            more_values, more_tables = leaves(t, where)
            values += more_values
            tables += more_tables
        if not inner:
            values.append((place, v))
    return values, tables


def numpy_of(value, rng):
    """numpy's type of the same value, or "" when the value is no number."""
    if isinstance(value, bool):
        return "np.bool_(%r)" % value
    if isinstance(value, int) and 0 <= value < 128:
        return "%s(%r)" % (rng.choice(NUMPY_INT), value)
    if isinstance(value, int):
        return "np.int64(%r)" % value
    if isinstance(value, float):
        import numpy as np
        return "%s(%r)" % ("np.float32" if float(np.float32(value)) == value and rng.random() < 0.5 else "np.float64",
                           value)
    return ""


def case_script(rng, scene_name):
    """The body of one case's script and what it does."""
    import tomllib
    with open(os.path.join(PROBLEMS, scene_name + ".toml"), "rb") as f:
        scene = tomllib.load(f)
    lines = ["scene = tomllib.load(open(%r, 'rb'))" % os.path.join(PROBLEMS, scene_name + ".toml")]
    kind = rng.choice(["hostile", "hostile", "numpy", "numpy", "huge", "nest", "table", "delete", "key", "source",
                       "set", "set", "keyword", "keyword", "threads"])
    source, kwargs, expect, allowed = "scene", {}, "", []
    places, tables = leaves(scene)
    place, value = rng.choice(places)
    if kind == "hostile":
        lines.append("scene%s = %s" % (place, rng.choice(HOSTILE)))
    elif kind == "numpy":
        numbers = [(p, v) for p, v in places if numpy_of(v, rng)]
        place, value = rng.choice(numbers)
        lines += ["plain = copy.deepcopy(scene)", "scene%s = %s" % (place, numpy_of(value, rng))]
        expect = "lambda: rollerpy.run(plain)"
    elif kind == "huge":
        lines.append("scene%s = %s" % (place, rng.choice(["2**70", "-2**70", "2**64", "2**63", "10**400"])))
    elif kind == "nest":
        depth = rng.choice([300, 1000, 100000])
        builder = rng.choice(["nest", "nest_list"])
        where = rng.choice(["scene%s" % place, "scene['x']", "scene['material']['E']"])
        lines.append("%s = %s(%d)" % (where, builder, depth))
    elif kind == "table":
        table = rng.choice(tables)
        lines.append("scene%s = %s" % (table, rng.choice(["5", "[]", "None", '"x"', 'b"x"', "[{}]", "{}"])))
    elif kind == "delete":
        lines.append("del scene%s" % rng.choice([place] + tables))
    elif kind == "key":
        table = rng.choice(["", rng.choice(tables)])
        lines.append("scene%s[%s] = 1" % (table, rng.choice(["1", "None", 'b"mesh"', "(1, 2)", "1.5", '""'])))
    elif kind == "source":
        source = rng.choice(SOURCES).replace("FILE", os.path.join(PROBLEMS, scene_name + ".toml"))
    elif kind == "set":
        kwargs["set"] = rng.choice(SETS)
        plain = {'{"steps.count": np.int64(2)}': '{"steps.count": 2}',
                 '{"material.E": np.float32(2e5)}': '{"material.E": 2e5}'}.get(kwargs["set"])
        expect = "lambda: rollerpy.run(scene, set=%s)" % plain if plain else ""
    elif kind == "keyword":
        name = rng.choice(sorted(KEYWORDS))
        kwargs[name] = rng.choice(KEYWORDS[name])
        if name == "progress" and kwargs[name] in ("stop", "lambda: None", "interrupt"):
            allowed = {"stop": ["ProgressStop"], "lambda: None": ["TypeError"],
                       "interrupt": ["RunInterrupted"]}[kwargs[name]]
    if kind == "threads":
        lines += [
            "outcomes = []",
            "def one(i):",
            "    call(lambda: rollerpy.run(scene), allowed=[])",
            "threads = [threading.Thread(target=one, args=(i,)) for i in range(2)]",
            "[t.start() for t in threads]",
            "[t.join() for t in threads]",
        ]
        return lines, "two threads run problems/%s.toml at once" % scene_name
    words = ", ".join([source] + ["%s=%s" % kv for kv in sorted(kwargs.items())])
    judged = (["like=" + expect] if expect else []) + (["allowed=%r" % allowed] if allowed else []) + \
        (["out=%s" % kwargs["out"]] if "out" in kwargs else [])
    lines.append("call(%s)" % ", ".join(["lambda: rollerpy.run(%s)" % words] + judged))
    return lines, "%s: %s" % (kind, "; ".join(lines[1:]))


def child_env():
    """PYTHONPATH with this package's python/ folder first."""
    paths = [os.path.join(ROOT, "python")] + [p for p in os.environ.get("PYTHONPATH", "").split(":") if p]
    return {"PYTHONPATH": ":".join(dict.fromkeys(paths))}


def judge(rc, output, timed_out, calls):
    if timed_out:
        return "hang (timeout)"
    if rc is None or rc < 0 or rc >= 128:
        return "crash (signal %s)" % (-rc if rc is not None and rc < 0 else rc)
    verdicts = [line[len("VERDICT "):] for line in output.splitlines() if line.startswith("VERDICT ")]
    failed = [v[len("fail "):] for v in verdicts if v.startswith("fail ")]
    if failed:
        return failed[0]
    if rc != 0 or len(verdicts) < calls:
        tail = [line for line in output.splitlines() if line.strip()][-1:] or ["no output"]
        return "the case script ended with exit %s and %d of %d verdicts: %s" % (
            rc, len(verdicts), calls, tail[0][:200])
    return ""


def main(argv=None):
    args = options("fuzz-python", __doc__, 60, 60.0).parse_args(argv)
    probe = subprocess.run([PYTHON, "-c", "import rollerpy._roller"], env=dict(os.environ, **child_env()),
                           capture_output=True, text=True)
    if probe.returncode != 0:
        reason = (probe.stderr.strip().splitlines() or ["exit %d" % probe.returncode])[-1]
        if args.sanitized:
            print("fuzz-python: skipped: rollerpy._roller does not import (%s); the sanitizer build does not "
                  "build it" % reason)
            return 0
        print("fuzz-python: rollerpy._roller does not import (%s): build it (scripts/build.sh)" % reason)
        return 1
    fuzz = Campaign("fuzz-python", args)
    for case in range(1, args.cases + 1):
        folder = fuzz.case_dir(case)
        os.mkfifo(os.path.join(folder, "fifo"))
        with open(os.path.join(folder, "file.txt"), "w") as f:
            f.write("a regular file\n")
        lines, what = case_script(fuzz.rng, fuzz.rng.choice(SCENES))
        script = os.path.join(folder, "case.py")
        with open(script, "w") as f:
            f.write("# %s\n" % what.replace("\n", " ") + PRELUDE + "\n".join(lines) + "\n")
        command = [PYTHON, script]
        result = run(command, os.path.join(folder, "output.txt"), args.timeout, child_env())
        output = result.output()
        problem = judge(result.exit_code, output, result.timed_out, 2 if "threads" in what[:20] else 1)
        outcome = "timeout" if result.timed_out else "crash" if problem.startswith("crash") else \
            ("pass" if not problem else "fail")
        fuzz.record(case, outcome, problem, what, command, output, [script], child_env(),
                    ["mkfifo %s 2> /dev/null; echo 'a regular file' > %s" % (
                        os.path.join(folder, "fifo"), os.path.join(folder, "file.txt"))])
    return fuzz.finish()


if __name__ == "__main__":
    sys.exit(main())
