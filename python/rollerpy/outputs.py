"""The tables of a roller output folder (docs/scenes.md, Outputs): the CSV files (roller.csv,
solver.csv, contact.csv, passes.csv, residual_depth.csv, ...), summary.json and
scene.resolved.toml, as rows, numbers or numpy arrays. The VTU/PVD files: rollerpy.vtu."""
import csv
import json
import math
import os
import re
import tomllib
from dataclasses import dataclass

import numpy as np


def read_rows(path, missing_ok=False):
    """A CSV file as a list of dicts (column -> text); [] for a missing file when missing_ok."""
    if missing_ok and not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_numbers(path, text_columns=("status",)):
    """A CSV file as a list of dicts of floats (the text_columns kept as text)."""
    return [{k: (v if k in text_columns else float(v)) for k, v in row.items()} for row in read_rows(path)]


def read_array(path, n_text=0):
    """A numeric CSV with a header as a numpy structured array; the first n_text columns are text
    (read separately: np.loadtxt is much faster than genfromtxt with converters)."""
    with open(path) as f:
        header = f.readline().strip().split(",")
        text = [line.split(",", n_text)[:n_text] for line in f] if n_text else []
    numbers = np.loadtxt(path, delimiter=",", skiprows=1, usecols=range(n_text, len(header)), ndmin=2)
    dtype = [(name, "U16") for name in header[:n_text]] + [(name, "f8") for name in header[n_text:]]
    data = np.empty(numbers.shape[0], dtype=dtype)
    for k, name in enumerate(header[:n_text]):
        data[name] = [row[k] for row in text]
    for k, name in enumerate(header[n_text:]):
        data[name] = numbers[:, k]
    return data


def num(text):
    """A CSV or JSON value as a float; nan when it is missing or not a number."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return float("nan")


def read_summary(out, missing_ok=False):
    """OUT/summary.json; {} when it is missing or not JSON and missing_ok."""
    try:
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        if missing_ok:
            return {}
        raise


def read_scene(out):
    """OUT/scene.resolved.toml: the scene as the run used it, every default filled in."""
    with open(os.path.join(out, "scene.resolved.toml"), "rb") as f:
        return tomllib.load(f)


def summary_field(summary, dotted):
    """A summary.json value by its dotted path (passes.verdict); None where there is none."""
    value = summary
    for part in dotted.split("."):
        value = value.get(part) if isinstance(value, dict) else None
    return value


CSV_PICKS = ("last", "max", "min")  # and step=N


def parse_collect(name):
    """A study's collect entry (docs/studies.md): a summary.json dotted path, or FILE.csv:COLUMN
    with an optional row choice :last (the default), :max, :min or :step=N. Returns None for a
    dotted path, else (file, column, pick, step); ValueError says what is wrong."""
    if ":" not in name:
        return None
    parts = name.split(":")
    if len(parts) > 3 or not parts[0].endswith(".csv") or not parts[1]:
        raise ValueError("expected FILE.csv:COLUMN, optionally :last, :max, :min or :step=N")
    # A file of the point's own output folder only: a study never reads outside it.
    if os.path.isabs(parts[0]) or ".." in re.split(r"[/\\]", parts[0]):
        raise ValueError("%s: expected a file of the point's output folder (a name such as passes.csv, "
                         "no absolute path and no '..')" % parts[0])
    pick = parts[2] if len(parts) == 3 else "last"
    if pick in CSV_PICKS:
        return parts[0], parts[1], pick, None
    step = pick[len("step="):] if pick.startswith("step=") else ""
    if not step.isdigit():
        raise ValueError("the row choice %r: expected last, max, min or step=N (N a step number)" % pick)
    return parts[0], parts[1], "step", int(step)


def csv_value(rows, column, pick, step):
    """The column's text in the row that `pick` chooses: the last row; the row of the largest or
    smallest number (rows whose cell is not a number skipped); the last row of step N. None when
    there is no such row or column."""
    if pick == "step":
        rows = [r for r in rows if num(r.get("step")) == step]
    if pick in ("max", "min"):
        rows = [r for r in rows if not math.isnan(num(r.get(column)))]
        rows = [(max if pick == "max" else min)(rows, key=lambda r: num(r[column]))] if rows else []
    return rows[-1].get(column) if rows else None


def collect(out, fields):
    """Values of a finished run: summary.json dotted paths, FILE.csv:COLUMN[:PICK] from a row of
    the file (parse_collect); None where the run did not write them."""
    summary = read_summary(out, missing_ok=True)
    values = {}
    for name in fields:
        spec = parse_collect(name)
        if spec is None:
            values[name] = summary_field(summary, name)
            continue
        path = os.path.realpath(os.path.join(out, spec[0]))
        if os.path.commonpath([path, os.path.realpath(out)]) != os.path.realpath(out):
            values[name] = None  # a link out of the folder: never followed
            continue
        try:
            values[name] = csv_value(read_rows(path), *spec[1:])
        except OSError:
            values[name] = None
    return values


def read_contact(out):
    """OUT/contact.csv: one row per candidate node and step (step, node, x, gap, p_n, p_t, status)."""
    return read_rows(os.path.join(out, "contact.csv"))


@dataclass
class ContactProfile:
    """The contact candidates of one step, sorted by x."""
    x: np.ndarray
    p_n: np.ndarray
    p_t: np.ndarray
    status: list


def contact_profile(rows, step):
    sel = sorted((r for r in rows if int(r["step"]) == step), key=lambda r: float(r["x"]))
    return ContactProfile(x=np.array([float(r["x"]) for r in sel]), p_n=np.array([float(r["p_n"]) for r in sel]),
                          p_t=np.array([float(r["p_t"]) for r in sel]), status=[r["status"] for r in sel])


def touching_x(rows, step):
    """x of the nodes in contact (status not open) at the step, sorted."""
    return sorted(float(r["x"]) for r in rows if int(r["step"]) == step and r["status"] != "open")


@dataclass
class RollerPose:
    xc: float
    yc: float
    radius: float


def roller_at(out, step):
    """The roller's centre and radius at a step (roller.csv, scene.resolved.toml), or None for a
    run without a roller."""
    path = os.path.join(out, "roller.csv")
    if not os.path.exists(path):
        return None
    radius = read_scene(out).get("roller", {}).get("radius")
    rows = [r for r in read_rows(path) if int(r["step"]) == step]
    return RollerPose(float(rows[-1]["xc"]), float(rows[-1]["yc"]), float(radius)) if rows and radius else None
