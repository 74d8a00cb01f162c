"""roller in the Python process (docs/python.md, "roller in process").

    import rollerpy
    run = rollerpy.run("problems/hertz.toml", set={"steps.count": 8})
    run.roller["fy"], run.field("von_mises_nodal"), run.mesh.points

A scene is a file or a dict of the scene file's tables; `set` overrides keys as `--set` does,
path segments included ("roller.path[1].fy"). Results come as numpy arrays, with the output
folder's files too when `out` is given. Ctrl-C stops the run after the step under way and raises
RunInterrupted (a KeyboardInterrupt) holding the results so far.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Callable, Optional, Union

import numpy as np

from rollerpy.outputs import read_rows

try:
    from rollerpy import _roller
except ImportError as e:  # the native module is built with roller (scripts/build.sh)
    raise ImportError(
        "rollerpy's native module _roller is not built: run scripts/build.sh (it builds "
        f"python/rollerpy/_roller*.so with Debian's pybind11-dev) ({e})") from e

InputError = _roller.InputError        # a scene or override refused (a ValueError)
ResourceError = _roller.ResourceError  # the machine refused: memory, disk (a RuntimeError)
Scene = _roller.Scene

SceneSource = Union[str, os.PathLike, dict, Scene]


def _require(ok: bool, name: str, value, expected: str) -> None:
    """InputError naming the argument, its value's type and what was expected."""
    if not ok:
        raise InputError(f"{name} = {value!r:.80}: a {type(value).__name__}; expected {expected}")


def _is_path(value) -> bool:
    return isinstance(value, (str, os.PathLike))


def load_scene(source: SceneSource, set: Optional[dict] = None,
               base_dir: Union[str, os.PathLike] = ".") -> Scene:
    """A checked scene from a file, a dict (relative paths in it from `base_dir`) or a Scene."""
    _require(_is_path(source) or isinstance(source, (dict, Scene)), "scene", source,
             "a scene file's path, a dict of its tables or a loaded Scene")
    _require(set is None or isinstance(set, dict), "set", set,
             "a dict of overrides {'key': value}, e.g. {'steps.count': 2}")
    _require(_is_path(base_dir), "base_dir", base_dir, "a folder's path")
    overrides = dict(set or {})
    if isinstance(source, Scene):
        if overrides:
            raise InputError("overrides need the scene's file or dict, not a loaded Scene")
        return source
    if isinstance(source, dict):
        return _roller.scene_from_dict(source, overrides, os.fspath(base_dir))
    return _roller.load_scene(os.fspath(source), overrides)


@dataclass(frozen=True)
class Mesh:
    points: np.ndarray  # (n_nodes, 2) reference coordinates [mm]
    cells: np.ndarray   # (n_elements, 3 or 4) node indices, counter-clockwise
    cell_type: str      # "Q4" or "T3"


@dataclass(frozen=True)
class StepFields:
    """The fields of one written step, by their VTU names (docs/scenes.md, Output)."""
    step: int
    pass_: int
    time: float
    point_data: dict    # name -> (n_nodes,) or (n_nodes, components)
    cell_data: dict     # name -> (n_elements,) or (n_elements, components)
    roller: Optional[dict]  # {"xc", "yc", "phi"} of the roller, None without one
    loaded: bool = False    # a stationary pass's loaded state beside the step's own fields

    def __getitem__(self, name: str) -> np.ndarray:
        if name in self.point_data:
            return self.point_data[name]
        if name in self.cell_data:
            return self.cell_data[name]
        raise KeyError(f"no field '{name}' at step {self.step}; the fields are "
                       f"{sorted(self.point_data) + sorted(self.cell_data)}")


@dataclass(frozen=True)
class RunResult:
    scene: str
    status: str          # as summary.json's: completed, step_failed, interrupted
    message: str
    steps: int           # the run's steps
    steps_done: int
    wall_s: float
    iterations: int
    mesh: Mesh
    tables: dict         # "solver", "roller", ... -> {column: array} (the CSV tables' columns)
    # StepFields of every written step, in order (a stationary pass's loaded state, loaded=True,
    # before its step's own)
    fields: list
    warnings: list
    verdict: Optional[dict] = None  # multi-pass runs: {"verdict", "criterion"}
    fatigue_answer: Optional[dict] = None  # with [fatigue]: summary.json's fatigue block (the last pass)
    summary: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return self.status == "completed"

    def table(self, name: str) -> dict:
        if name not in self.tables:
            raise KeyError(f"no table '{name}' in this run; it has {sorted(self.tables)}")
        return self.tables[name]

    solver = property(lambda self: self.table("solver"))
    roller = property(lambda self: self.table("roller"))
    contact = property(lambda self: self.table("contact"))
    passes = property(lambda self: self.table("passes"))
    residual_depth = property(lambda self: self.table("residual_depth"))
    fatigue = property(lambda self: self.table("fatigue"))

    @property
    def written_steps(self) -> list:
        return [f.step for f in self.fields if not f.loaded]

    def at_step(self, step: int = -1, loaded: bool = False) -> StepFields:
        """The fields of a written step (-1: the last one written); loaded=True: a stationary pass's
        loaded state (the strip under the roller) instead of the residual strip after it."""
        chosen = [f for f in self.fields if f.loaded == loaded]
        if not chosen:
            raise KeyError("this run wrote no %sfields (output.vtu = false, or it failed at once)"
                           % ("loaded " if loaded else ""))
        if step == -1:
            return chosen[-1]
        for f in chosen:
            if f.step == step:
                return f
        raise KeyError(f"step {step} was not written; the written steps are {[f.step for f in chosen]}")

    def field(self, name: str, step: int = -1, loaded: bool = False) -> np.ndarray:
        return self.at_step(step, loaded)[name]


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C stopped the run after the step under way; `result` holds the steps done."""

    def __init__(self, result: RunResult):
        hint = " (in Python: rollerpy.run(scene, out=..., resume=True))" if "--resume" in result.message else ""
        super().__init__(f"roller: {result.message}{hint}")
        self.result = result


def run(scene: SceneSource, *, set: Optional[dict] = None,
        out: Optional[Union[str, os.PathLike]] = None, overwrite: bool = False,
        progress: Optional[Callable[[dict], None]] = None,
        verbose: bool = False, resume: bool = False) -> RunResult:
    """Runs a scene in this process.

    out: also write the output folder (as `roller run --out`); None writes no file.
    progress: called after every step with its row of solver.csv (a dict) and "steps", the
    run's step count. An exception it raises stops the run after that step and is raised again.
    verbose: roller's progress lines on standard output.
    resume: go on from the checkpoint in `out` (as `roller run --resume`) of a run that stopped
    (Ctrl-C, a killed process); the tables are then the folder's, the whole run's, and `fields`
    those of the steps this call ran.
    """
    _require(out is None or _is_path(out), "out", out, "None or an output folder's path")
    for name, flag in (("overwrite", overwrite), ("verbose", verbose), ("resume", resume)):
        _require(isinstance(flag, (bool, np.bool_)), name, flag, "True or False")
    _require(progress is None or callable(progress), "progress", progress,
             "None or a function called with each step's row")
    overwrite, verbose, resume = bool(overwrite), bool(verbose), bool(resume)
    if resume and out is None:
        raise InputError("resume=True: give out, the folder of the run to resume (its checkpoint.cbor)")
    loaded = load_scene(scene, set)
    raw = _roller.run(loaded, None if out is None else os.fspath(out), overwrite, progress, verbose, resume)
    if resume:
        raw["tables"] = _folder_tables(os.fspath(out), raw["tables"], raw["table_files"])
    result = _result(raw)
    error = raw["error"]
    if isinstance(error, KeyboardInterrupt):
        raise RunInterrupted(result) from error
    if error is not None:
        raise error
    return result


def _column(texts: list, like: Optional[np.ndarray]) -> np.ndarray:
    """A CSV column as the run's own tables hold it: of the type of `like` (this call's column),
    else int64 when every cell is an integer, str when any is text, float64 otherwise. A column that
    is numeric in this call's steps but has empty cells in the folder's earlier ones (an optional
    value, such as roller.csv's effective_radius at step 0) is str, as a whole run's would be."""
    if like is not None and like.dtype.kind in "iuf" and all(texts):
        return np.array([float(t) for t in texts], dtype=like.dtype) if like.dtype.kind == "f" else \
            np.array([int(t) for t in texts], dtype=like.dtype)
    if like is not None:
        return np.array(texts, dtype=str)
    try:
        return np.array([int(t) for t in texts], dtype=np.int64)
    except ValueError:
        pass
    try:
        return np.array([float(t) for t in texts], dtype=np.float64)
    except ValueError:
        return np.array(texts, dtype=str)


def _folder_tables(out: str, tables: dict, files: dict) -> dict:
    """The tables of the output folder's CSV files (a resumed run's whole record): every table the
    scene's run fills (`files`: name -> file), typed as this call's own `tables`."""
    folder = {}
    for name, file in sorted(files.items()):
        rows = read_rows(os.path.join(out, file), missing_ok=True)
        own = tables.get(name, {})
        folder[name] = {c: _column([r[c] for r in rows], own.get(c)) for c in (rows[0] if rows else own)}
    return folder


def _result(raw: dict) -> RunResult:
    s = raw["summary"]
    fields = [StepFields(f["step"], f["pass"], f["time"], f["point_data"], f["cell_data"],
                         f["roller"], f["loaded"]) for f in raw["fields"]]
    m = raw["mesh"]
    return RunResult(scene=raw["scene"], status=s["status"], message=s["message"],
                     steps=raw["steps"], steps_done=s["steps_done"], wall_s=s["wall_s"],
                     iterations=s["iterations"],
                     mesh=Mesh(m["points"], m["cells"], m["cell_type"]), tables=raw["tables"],
                     fields=fields, warnings=list(raw["warnings"]), verdict=raw.get("verdict"),
                     fatigue_answer=raw.get("fatigue"), summary=s)


def version() -> dict:
    """roller's version, commit, and its Ipopt and MUMPS."""
    return _roller.version()
