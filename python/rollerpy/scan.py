"""nan and inf in a run's outputs (docs/stability.md, "No nan or inf in any output"): every CSV
cell, JSON value (nlohmann writes NaN as null, so null counts too), every DataArray of every VTU
file (decoded, rollerpy.vtu; a file that does not decode is malformed), every float of a CBOR
state file, and nan/inf tokens in any other text file (pvd, toml, the log)."""
import csv
import enum
import json
import math
import os
import re
import struct
import tempfile
from dataclasses import dataclass, field

import numpy as np

from .vtu import VtuError, decode_vtu, write_test_vtu

NONFINITE_TOKEN = re.compile(r"(?<![A-Za-z_])[-+]?(nan|inf|infinity)(?![A-Za-z_])", re.I)


class Finding(str, enum.Enum):
    CLEAN = ""
    NONFINITE = "nonfinite"
    MALFORMED = "malformed"


@dataclass
class FileScan:
    """What the scan found in one file: `count` non-finite values, or why it could not be read
    (malformed); `messages` say where; `arrays`: the VTU arrays decoded."""
    finding: Finding = Finding.CLEAN
    count: int = 0
    messages: list = field(default_factory=list)
    arrays: int = 0

    def describe(self):
        """The count, or the reason a file could not be read (the stability tables' form)."""
        return self.messages[0] if self.finding == Finding.MALFORMED else self.count


def _counted(count, messages, arrays=0):
    return FileScan(Finding.NONFINITE if count else Finding.CLEAN, count, messages, arrays)


def cbor_floats(data):
    """All floats of a CBOR document (a linear scan of the data item heads)."""
    out, i, n = [], 0, len(data)
    while i < n:
        b = data[i]
        major, ai = b >> 5, b & 31
        i += 1
        if major == 7:
            width = {25: 2, 26: 4, 27: 8}.get(ai)
            if width:
                out.append(struct.unpack({2: ">e", 4: ">f", 8: ">d"}[width], data[i:i + width])[0])
                i += width
            elif ai == 24:
                i += 1
            continue
        if ai < 24:
            length = ai
        elif ai in (24, 25, 26, 27):
            size = 1 << (ai - 24)
            length = int.from_bytes(data[i:i + size], "big")
            i += size
        elif ai == 31:
            length = 0  # indefinite length: the items follow, a break (0xff) ends them
        else:
            raise ValueError("bad CBOR head 0x%02x at byte %d" % (b, i - 1))
        if major in (2, 3):
            i += length
    return out


def json_nonfinite(value):
    if value is None:
        return 1
    if isinstance(value, float):
        return 0 if math.isfinite(value) else 1
    if isinstance(value, dict):
        return sum(json_nonfinite(v) for v in value.values())
    if isinstance(value, list):
        return sum(json_nonfinite(v) for v in value)
    return 0


def vtu_nonfinite(arrays):
    """One message per floating-point array holding nan or inf, and their total count."""
    found, total = [], 0
    for section, name, values in arrays:
        if values.dtype.kind != "f":
            continue
        bad = ~np.isfinite(values)
        n = int(np.count_nonzero(bad))
        if n:
            total += n
            t, c = (int(i) for i in np.argwhere(bad)[0])
            found.append("%s '%s': %d non-finite value%s (first %r at tuple %d, component %d)" % (
                section, name, n, "s" if n > 1 else "", float(values[t, c]), t, c))
    return found, total


def _scan_csv(path):
    count, messages = 0, []
    with open(path, newline="") as f:
        for number, row in enumerate(csv.reader(f), 1):
            for cell in row:
                c = cell.strip()
                try:
                    bad = bool(NONFINITE_TOKEN.fullmatch(c)) or not math.isfinite(float(c))
                except ValueError:
                    bad = False
                if bad:
                    count += 1
                    messages.append("line %d: %s" % (number, c))
    return _counted(count, messages[:3] + (["..."] if len(messages) > 3 else []))


def _scan_text(path):
    count, messages = 0, []
    with open(path, errors="replace") as f:
        for number, line in enumerate(f, 1):
            tokens = NONFINITE_TOKEN.findall(line)
            count += len(tokens)
            messages += ["line %d: %s" % (number, t) for t in tokens]
    return _counted(count, messages[:3] + (["..."] if len(messages) > 3 else []))


def scan_file(path):
    """The FileScan of one output file, by its ending."""
    ext = os.path.splitext(path)[1]
    if ext == ".vtu":
        try:
            arrays = decode_vtu(path)
        except VtuError as e:
            return FileScan(Finding.MALFORMED, messages=["unreadable VTU (%s)" % e])
        found, total = vtu_nonfinite(arrays)
        return _counted(total, found, len(arrays))
    if ext == ".csv":
        return _scan_csv(path)
    if ext == ".json":
        try:
            with open(path) as f:
                count = json_nonfinite(json.load(f))
        except ValueError as e:
            return FileScan(Finding.MALFORMED, messages=["invalid JSON (%s)" % e])
        return _counted(count, ["%d null or non-finite value%s" % (count, "s" if count > 1 else "")] if count else [])
    if ext == ".cbor":
        with open(path, "rb") as f:
            data = f.read()
        try:
            count = sum(not math.isfinite(v) for v in cbor_floats(data))
        except (ValueError, struct.error) as e:
            return FileScan(Finding.MALFORMED, messages=["unreadable CBOR (%s)" % e])
        return _counted(count, ["%d non-finite float%s" % (count, "s" if count > 1 else "")] if count else [])
    return _scan_text(path)


def files_under(folder):
    """Every file under folder, in a stable order."""
    return [os.path.join(d, n) for d, _, names in sorted(os.walk(folder)) for n in sorted(names)]


@dataclass
class FolderScan:
    """What the scan of an output folder found: the files that are not clean, as (path, FileScan),
    and how much it read."""
    flagged: list
    files: int
    vtu_files: int
    arrays: int

    def problems(self, out):
        """The stability tables' lines: "<path relative to OUT's folder>: <count or reason>"."""
        return ["%s: %s" % (os.path.relpath(p, os.path.dirname(out)), r.describe()) for p, r in self.flagged]


def scan_outputs(out, log=None, endings=None):
    """Scans every file under `out` (and the log); endings: only the files with these endings."""
    files = ([log] if log and os.path.exists(log) else []) + files_under(out)
    if endings:
        files = [p for p in files if p.endswith(tuple(endings))]
    flagged, arrays = [], 0
    for path in files:
        result = scan_file(path)
        arrays += result.arrays
        if result.finding != Finding.CLEAN:
            flagged.append((path, result))
    return FolderScan(flagged, len(files), sum(p.endswith(".vtu") for p in files), arrays)


def self_check():
    """The scan must be able to fail: planted nan/inf values in CSV, JSON and VTU files
    (zlib-compressed and raw) are found, a clean VTU passes and a cut VTU array is malformed.
    Returns what went wrong (empty when the scanner works)."""
    wrong = []
    with tempfile.TemporaryDirectory() as d:
        def check(name, expected, count=None):
            result = scan_file(os.path.join(d, name))
            if result.finding != expected or (count is not None and result.count != count):
                wrong.append("%s: scanned as %r (%d; %s), expected %r" % (
                    name, result.finding.value, result.count, "; ".join(result.messages), expected.value))

        planted = {"a.csv": "step,fx\n1,0.5\n2,nan\n", "b.csv": "step,fx\n1,-inf\n", "c.csv": "step,fx\n2,-nan\n",
                   "d.json": '{"fx": null}\n'}
        for name, text in planted.items():
            with open(os.path.join(d, name), "w") as f:
                f.write(text)
            check(name, Finding.NONFINITE, 1)
        u = np.arange(8.0).reshape(4, 2)
        for compressed in (True, False):
            tag = "z" if compressed else "raw"
            write_test_vtu(os.path.join(d, "clean_%s.vtu" % tag), u, compressed)
            check("clean_%s.vtu" % tag, Finding.CLEAN)
            for bad in (np.nan, -np.inf):
                v = u.copy()
                v[3, 1] = bad
                write_test_vtu(os.path.join(d, "bad_%s_%s.vtu" % (tag, bad)), v, compressed)
                check("bad_%s_%s.vtu" % (tag, bad), Finding.NONFINITE, 1)
            write_test_vtu(os.path.join(d, "short_%s.vtu" % tag), u[:3], compressed)
            check("short_%s.vtu" % tag, Finding.MALFORMED)
    return wrong
