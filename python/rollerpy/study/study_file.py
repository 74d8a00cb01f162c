"""A study file (TOML; docs/studies.md): a base scene, fixed --set values, the parameters to vary
(a grid, or a list of points), the backends, what to collect. load() checks everything before a
point runs and raises StudyError naming the file, the key, the value and what was expected."""
import itertools
import math
import os
import tomllib
from dataclasses import dataclass, field

from ..outputs import parse_collect

TOP_KEYS = {"title", "scene", "backends", "timeout", "collect", "set", "grid", "point"}
BACKENDS = ("ipopt", "penalty")
RUNNER_COLUMNS = ("index", "backend", "status", "message", "wall_s", "out")


class StudyError(ValueError):
    pass


@dataclass
class Point:
    index: int
    backend: str
    values: dict  # --set key -> value (the varied parameters only)

    @property
    def name(self):
        return "p%03d_%s" % (self.index, self.backend) if self.backend else "p%03d" % self.index


@dataclass
class Study:
    path: str
    title: str
    scene: str                  # absolute path of the base scene
    backends: list              # None: the scene's own backend
    timeout: float              # per point [s]
    collect: list               # summary.json dotted paths, or FILE.csv:COLUMN[:last|max|min|step=N]
    fixed: dict                 # --set for every point
    parameters: list            # the varied keys, in order
    points: list = field(default_factory=list)


def _fail(path, key, value, expected):
    raise StudyError("%s: %s = %r: %s" % (path, key, value, expected))


def _expand(path, key, spec):
    """A parameter's values: a list, or a range {start, stop, count} (both ends included) or
    {start, stop, step} (stop included when a whole number of steps reaches it)."""
    if isinstance(spec, list):
        if not spec:
            _fail(path, "grid." + key, spec, "expected a non-empty list of values or a range")
        return spec
    if not isinstance(spec, dict):
        _fail(path, "grid." + key, spec, "expected a list of values or a range {start, stop, count|step}")
    unknown = set(spec) - {"start", "stop", "count", "step"}
    if unknown:
        _fail(path, "grid.%s.%s" % (key, sorted(unknown)[0]), spec[sorted(unknown)[0]],
              "unknown range key; expected start, stop and count or step")
    for k in ("start", "stop"):
        v = spec.get(k)
        if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
            _fail(path, "grid.%s.%s" % (key, k), v, "expected a finite number")
    start, stop = float(spec["start"]), float(spec["stop"])
    if ("count" in spec) == ("step" in spec):
        _fail(path, "grid." + key, spec, "a range needs exactly one of count and step")
    if "count" in spec:
        n = spec["count"]
        if not isinstance(n, int) or isinstance(n, bool) or not 1 <= n <= 100000:
            _fail(path, "grid.%s.count" % key, n, "expected an integer 1 <= count <= 100000")
        if n == 1:
            if start != stop:
                _fail(path, "grid.%s.count" % key, n, "one value needs start = stop")
            return [start]
        return [start + (stop - start) * i / (n - 1) for i in range(n)]
    step = spec["step"]
    if not isinstance(step, (int, float)) or isinstance(step, bool) or not math.isfinite(step) or step == 0.0:
        _fail(path, "grid.%s.step" % key, step, "expected a finite number != 0")
    if (stop - start) * step < 0.0:
        _fail(path, "grid.%s.step" % key, step, "the step must go from start = %g towards stop = %g" % (start, stop))
    n = int(math.floor((stop - start) / step + 1e-9)) + 1
    if n > 100000:
        _fail(path, "grid.%s.step" % key, step, "gives %d values; at most 100000" % n)
    return [start + i * step for i in range(n)]


def _check_set_key(path, where, key):
    if not isinstance(key, str) or not key or any(c.isspace() for c in key) or "=" in key:
        _fail(path, where, key, "expected a scene key as --set takes it, e.g. material.E")


def load(path):
    path = os.path.abspath(path)
    try:
        with open(path, "rb") as f:
            doc = tomllib.load(f)
    except OSError as e:
        raise StudyError("%s: cannot read: %s" % (path, e.strerror))
    except tomllib.TOMLDecodeError as e:
        raise StudyError("%s: not valid TOML: %s" % (path, e))
    except RecursionError:  # tomllib parses nested arrays and inline tables recursively
        raise StudyError("%s: arrays or inline tables nested too deeply for a study file (docs/studies.md)" % path)
    unknown = sorted(set(doc) - TOP_KEYS)
    if unknown:
        _fail(path, unknown[0], doc[unknown[0]], "unknown key; expected one of %s" % ", ".join(sorted(TOP_KEYS)))
    scene = doc.get("scene")
    if not isinstance(scene, str):
        _fail(path, "scene", scene, "expected the base scene's path (relative to the study file)")
    scene = os.path.normpath(os.path.join(os.path.dirname(path), scene))
    if not os.path.isfile(scene):
        _fail(path, "scene", doc["scene"], "no such file (%s)" % scene)
    backends = doc.get("backends")  # absent: the scene's own (or none: a scene without a roller)
    if backends is not None and (not isinstance(backends, list) or not backends
                                 or any(b not in BACKENDS for b in backends) or len(set(backends)) != len(backends)):
        _fail(path, "backends", backends, "expected a list of distinct backends from %s" % ", ".join(BACKENDS))
    backends = backends or [None]
    timeout = doc.get("timeout", 3600)
    if not isinstance(timeout, (int, float)) or isinstance(timeout, bool) or not 0 < timeout <= 1e7:
        _fail(path, "timeout", timeout, "expected seconds per point, 0 < timeout <= 1e7")
    collect = doc.get("collect", [])
    if not isinstance(collect, list) or any(not isinstance(c, str) or not c for c in collect):
        _fail(path, "collect", collect, "expected a list of summary.json fields (a.b) or FILE.csv:COLUMN[:PICK]")
    for c in collect:
        try:
            parse_collect(c)
        except ValueError as e:
            _fail(path, "collect", c, str(e))
    clash = [c for c in collect if c in RUNNER_COLUMNS]
    if clash:
        _fail(path, "collect", clash[0], "study.csv has this column already (the runner's: %s)"
              % ", ".join(RUNNER_COLUMNS))
    fixed = doc.get("set", {})
    if not isinstance(fixed, dict):
        _fail(path, "set", fixed, "expected a table of --set keys and values")
    for k in fixed:
        _check_set_key(path, "set", k)
    if ("grid" in doc) == ("point" in doc):
        raise StudyError("%s: give the varied parameters either as [grid] (every combination) or as "
                         "[[point]] blocks (a list), exactly one of them" % path)
    combos = []
    if "grid" in doc:
        grid = doc["grid"]
        if not isinstance(grid, dict) or not grid:
            _fail(path, "grid", grid, "expected a table: scene key = list of values or a range")
        for k in grid:
            _check_set_key(path, "grid", k)
        parameters = list(grid)
        values = [_expand(path, k, grid[k]) for k in parameters]
        combos = [dict(zip(parameters, c)) for c in itertools.product(*values)]
    else:
        blocks = doc["point"]
        if not isinstance(blocks, list) or not blocks or any(not isinstance(b, dict) or not b for b in blocks):
            _fail(path, "point", blocks, "expected [[point]] blocks, each a table of scene keys and values")
        parameters = []
        for b in blocks:
            for k in b:
                _check_set_key(path, "point", k)
                if k not in parameters:
                    parameters.append(k)
        for i, b in enumerate(blocks):
            missing = [k for k in parameters if k not in b]
            if missing:
                _fail(path, "point[%d]" % i, b, "every point must set the same keys; missing %s" % missing[0])
        combos = [dict(b) for b in blocks]
    overlap = sorted(set(parameters) & set(fixed))
    if overlap:
        _fail(path, "set." + overlap[0], fixed[overlap[0]], "is varied as well; give it in one place")
    if len(combos) * len(backends) > 100000:
        raise StudyError("%s: %d points: at most 100000" % (path, len(combos) * len(backends)))
    title = doc.get("title", os.path.splitext(os.path.basename(path))[0])
    study = Study(path=path, title=str(title), scene=scene, backends=backends, timeout=float(timeout),
                  collect=collect, fixed=fixed, parameters=parameters)
    index = 0
    for values in combos:
        for backend in backends:
            study.points.append(Point(index=index, backend=backend, values=values))
            index += 1
    return study


def toml_value(value):
    """A value as --set takes it: a TOML literal (strings quoted, tables inline)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str):
        return '"%s"' % value.replace("\\", "\\\\").replace('"', '\\"')
    if isinstance(value, list):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join("%s = %s" % (k, toml_value(v)) for k, v in value.items()) + "}"
    raise StudyError("cannot pass %r to --set" % (value,))
