#!/usr/bin/python3
"""Mutation fuzzer for scene files, --set values and command-line options (docs/stability.md,
"Hostile input").

usage: /usr/bin/python3 scripts/fuzz_scenes.py [--cases 200] [--seed 1] [--roller ./build/roller]
                                               [--out out/fuzz] [--timeout 30] [--steps 2]
                                               [--sanitized]
       /usr/bin/python3 scripts/fuzz_scenes.py --scan FILE_OR_FOLDER...

Each case takes a shipped scene (problems/*.toml), mutates it (a line deleted or duplicated, a
value replaced by nan/inf/huge/tiny/negative/wrong-typed ones, the file truncated, binary garbage
inserted, deeply nested dotted keys, or a --set override of a random key with such a value) and
runs `roller run` on it for a few steps (--steps, default 2) under a timeout. One case in three
also varies the command line: one or more of `--steps 1|2|3` (instead of the default),
`--contact penalty|ipopt`, `--refine 1|2` (`--refine 2` with `--steps 1`), now and then an
invalid value of one of them (which must end in exit 2).

A case passes when roller ends with a documented exit code (0 converged, 1 a step failed with an
"error:" line, 2 input error with "input error" or CLI11's "Run with --help", 3 a system error
such as a full disk) and no output file holds nan or inf. The output folder is scanned
recursively: the text of every CSV, JSON, PVD and TOML file for nan/inf/null tokens, and every
VTU file (step_NNNN.vtu) decoded array by array with numpy -- inline base64 binary data, raw or
zlib-compressed (vtkZLibDataCompressor blocks; header_type UInt32 or UInt64), or ascii -- for
non-finite Float32/Float64 values; a VTU whose arrays cannot be decoded or do not match the
piece's point and cell counts is malformed. A case fails on
  - a sanitizer report in roller's output ("ERROR: AddressSanitizer", "ERROR: LeakSanitizer",
    UBSan's "runtime error:"), whatever the exit code;
  - a crash (signal), a timeout (hang);
  - an internal error (exit 4, "roller: internal error:") or "roller: error:";
  - an undocumented exit code, or exit 1/2/3 without its message;
  - "exit 0 (converged) but nan/inf in an output": the run claimed success with a non-finite
    value in a file;
  - "nan/inf in an output after exit N" (a failed run must not write non-finite values either);
  - a malformed VTU file.
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
(scripts/test_sanitized.sh). A long run for a night: --cases 10000 --seed $RANDOM.
"""
import argparse
import base64
import binascii
import os
import random
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
import zlib

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Scenes that run on their own (z3_data02 needs z3_data01's final state); small ones weigh more.
SEEDS = ["block_compression", "hertz", "cattaneo", "bar_impact", "z1_outf05", "z2_infini", "z2_large",
         "z4_v25", "stability_thin", "rolling_friction", "hertz_nu049", "block_compression", "hertz",
         "cattaneo_mindlin", "burnishing"]
# For a Debug + ASan binary (--sanitized): the scenes whose first two steps take at most 0.2 s
# with the release build (burnishing: 0.3 s for one step, 1 s when a mutation makes it fail).
SMALL_SEEDS = [s for s in SEEDS if s != "burnishing"]
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
TEXT_NONFINITE = re.compile(r"(?<![A-Za-z_])(nan|inf|NaN|Inf|null)(?![A-Za-z_])")
TEXT_OUTPUTS = (".csv", ".json", ".pvd", ".toml")
SCANNED = {"files": 0, "vtu": 0, "arrays": 0}  # what the scan of the runs' outputs looked at


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
    an invalid value."""
    if rng.random() >= 1.0 / 3.0:
        return ["--steps", str(default_steps)], ""
    if rng.random() < 0.1:
        bad = list(rng.choice(BAD_OPTIONS))
        steps = [] if bad[0] == "--steps" else ["--steps", str(default_steps)]
        return steps + bad, " ".join(bad)
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
    return ["--steps", str(steps)] + extra, what


def scene_keys(roller):
    out = subprocess.run([roller, "scene-keys"], capture_output=True, text=True, check=True, env=roller_env()).stdout
    keys = []
    for line in out.splitlines()[1:]:
        k = line.split()[0] if line.split() else ""
        if k and "[]" not in k and "." in k:
            keys.append(k)
    return keys


# ---------------------------------------------------------------- VTU decoding

class VtuError(Exception):
    """A VTU file (or one of its arrays) that cannot be decoded or contradicts its piece."""


VTK_TYPES = {"Int8": "i1", "UInt8": "u1", "Int16": "<i2", "UInt16": "<u2", "Int32": "<i4", "UInt32": "<u4",
             "Int64": "<i8", "UInt64": "<u8", "Float32": "<f4", "Float64": "<f8"}
HEADER_TYPES = {"UInt32": "<u4", "UInt64": "<u8"}


def b64decode(text, what):
    try:
        return base64.b64decode(text, validate=True)
    except (binascii.Error, ValueError) as e:
        raise VtuError("%s: bad base64 (%s)" % (what, e))


def decode_binary(text, header_dtype, compressed, what):
    """The payload bytes of one inline format="binary" DataArray as vtu_writer.cpp writes it:
    uncompressed, base64 of [byte count][payload]; compressed, base64 of the header [number of
    blocks, block size, size of the last partial block (0 if full), compressed size of each block]
    followed by base64 of the deflated blocks."""
    text = re.sub(r"\s+", "", text or "")
    h = np.dtype(header_dtype).itemsize
    if not compressed:
        raw = b64decode(text, what)
        if len(raw) < h:
            raise VtuError("%s: %d bytes, shorter than its header" % (what, len(raw)))
        n = int(np.frombuffer(raw[:h], header_dtype)[0])
        if len(raw) - h != n:
            raise VtuError("%s: header says %d bytes, %d follow" % (what, n, len(raw) - h))
        return raw[h:]
    first_chars = 4 * ((h + 2) // 3)
    n_blocks = int(np.frombuffer(b64decode(text[:first_chars], what)[:h], header_dtype)[0])
    if n_blocks > len(text):
        raise VtuError("%s: %d blocks in a %d-character array" % (what, n_blocks, len(text)))
    header_bytes = h * (3 + n_blocks)
    header_chars = 4 * ((header_bytes + 2) // 3)
    header = b64decode(text[:header_chars], what)[:header_bytes]
    if len(header) < header_bytes:
        raise VtuError("%s: compression header cut short" % what)
    header = [int(v) for v in np.frombuffer(header, header_dtype)]
    block_size, last_size, sizes = header[1], header[2], header[3:]
    data = b64decode(text[header_chars:], what)
    if sum(sizes) != len(data):
        raise VtuError("%s: compressed block sizes sum to %d bytes, %d follow" % (what, sum(sizes), len(data)))
    out, pos = [], 0
    for b, size in enumerate(sizes):
        try:
            block = zlib.decompress(data[pos:pos + size])
        except zlib.error as e:
            raise VtuError("%s: block %d does not inflate (%s)" % (what, b, e))
        expected = last_size if b == n_blocks - 1 and last_size else block_size
        if len(block) != expected:
            raise VtuError("%s: block %d inflates to %d bytes, expected %d" % (what, b, len(block), expected))
        out.append(block)
        pos += size
    return b"".join(out)


def decode_vtu(path):
    """Every DataArray of an UnstructuredGrid VTU file as (section, name, numpy array of shape
    (tuples, components)); raises VtuError when the file is malformed."""
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise VtuError("not XML (%s)" % e)
    if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
        raise VtuError("not a VTKFile of type UnstructuredGrid")
    if root.get("byte_order", "LittleEndian") != "LittleEndian":
        raise VtuError("byte_order %s" % root.get("byte_order"))
    header_dtype = HEADER_TYPES.get(root.get("header_type", "UInt32"))
    if header_dtype is None:
        raise VtuError("header_type %s" % root.get("header_type"))
    compressor = root.get("compressor")
    if compressor not in (None, "vtkZLibDataCompressor"):
        raise VtuError("compressor %s" % compressor)
    pieces = root.findall("UnstructuredGrid/Piece")
    if not pieces:
        raise VtuError("no UnstructuredGrid/Piece")
    arrays = []
    for k, piece in enumerate(pieces):
        try:
            n_points = int(piece.get("NumberOfPoints"))
            n_cells = int(piece.get("NumberOfCells"))
        except (TypeError, ValueError):
            raise VtuError("piece %d: NumberOfPoints/NumberOfCells missing or not integers" % k)
        counts = {"PointData": n_points, "CellData": n_cells, "Points": n_points, "Cells": n_cells}
        decoded = {}
        for section in ("PointData", "CellData", "Points", "Cells"):
            for node in piece.findall(section):
                for array in node.findall("DataArray"):
                    name = array.get("Name", "")
                    what = "%s/%s" % (section, name)
                    dtype = VTK_TYPES.get(array.get("type"))
                    if dtype is None:
                        raise VtuError("%s: type %s" % (what, array.get("type")))
                    fmt = array.get("format")
                    if fmt == "binary":
                        raw = decode_binary(array.text, header_dtype, compressor is not None, what)
                        if len(raw) % np.dtype(dtype).itemsize:
                            raise VtuError("%s: %d bytes, not a whole number of %s" % (
                                what, len(raw), array.get("type")))
                        values = np.frombuffer(raw, dtype)
                    elif fmt == "ascii":
                        try:
                            values = np.array((array.text or "").split(), dtype=float).astype(dtype)
                        except ValueError as e:
                            raise VtuError("%s: %s" % (what, e))
                    else:
                        raise VtuError("%s: format=%s is not decoded by this scanner (roller writes inline "
                                       "binary)" % (what, fmt))
                    nc = int(array.get("NumberOfComponents", "1"))
                    if nc < 1:
                        raise VtuError("%s: NumberOfComponents %d" % (what, nc))
                    if section == "Cells" and name == "connectivity":
                        n_tuples = None  # checked against the offsets below
                    else:
                        n_tuples = counts[section]
                    if n_tuples is not None and values.size != n_tuples * nc:
                        raise VtuError("%s: %d values, expected %d (%d tuples x %d components)" % (
                            what, values.size, n_tuples * nc, n_tuples, nc))
                    if values.size % nc:
                        raise VtuError("%s: %d values for %d components" % (what, values.size, nc))
                    decoded[(section, name)] = values
                    arrays.append((section, name, values.reshape(-1, nc)))
        points = [v for (s, _), v in decoded.items() if s == "Points"]
        if len(points) != 1 or points[0].size != 3 * n_points:
            raise VtuError("piece %d: no Points array of %d x 3 values" % (k, n_points))
        conn, offsets = decoded.get(("Cells", "connectivity")), decoded.get(("Cells", "offsets"))
        if conn is None or offsets is None or ("Cells", "types") not in decoded:
            raise VtuError("piece %d: Cells without connectivity, offsets and types" % k)
        if n_cells and (np.any(np.diff(offsets) < 0) or offsets[0] < 0 or int(offsets[-1]) != conn.size):
            raise VtuError("piece %d: offsets do not partition the %d connectivity entries" % (k, conn.size))
        if conn.size and (conn.min() < 0 or conn.max() >= n_points):
            raise VtuError("piece %d: connectivity refers to points outside 0..%d" % (k, n_points - 1))
    return arrays


def vtu_nonfinite(arrays):
    """One message per floating-point array holding nan or inf."""
    found = []
    for section, name, values in arrays:
        if values.dtype.kind != "f":
            continue
        bad = ~np.isfinite(values)
        n = int(np.count_nonzero(bad))
        if n:
            t, c = (int(i) for i in np.argwhere(bad)[0])
            found.append("%s '%s': %d non-finite value%s (first %r at tuple %d, component %d)" % (
                section, name, n, "s" if n > 1 else "", float(values[t, c]), t, c))
    return found


def scan_file(path):
    """(kind, messages) of one output file: kind "" (clean), "nonfinite" or "malformed"."""
    if path.endswith(".vtu"):
        SCANNED["files"] += 1
        SCANNED["vtu"] += 1
        try:
            arrays = decode_vtu(path)
        except VtuError as e:
            return "malformed", [str(e)]
        SCANNED["arrays"] += len(arrays)
        found = vtu_nonfinite(arrays)
        return ("nonfinite" if found else ""), found
    if path.endswith(TEXT_OUTPUTS):
        SCANNED["files"] += 1
        with open(path, errors="replace") as f:
            found = []
            for number, line in enumerate(f, 1):
                m = TEXT_NONFINITE.search(line)
                if m:
                    found.append("line %d: %s" % (number, m.group(1)))
        return ("nonfinite" if found else ""), found[:3] + (["..."] if len(found) > 3 else [])
    return "", []


def scan_outputs(out_dir):
    """[(kind, path, messages)] of every flagged file under out_dir."""
    flagged = []
    for d, _, names in sorted(os.walk(out_dir)):
        for name in sorted(names):
            path = os.path.join(d, name)
            kind, messages = scan_file(path)
            if kind:
                flagged.append((kind, path, messages))
    return flagged


def encode_vtu_array(values, compressed, block=32768):
    """A Float64/Int64/UInt8 array encoded as vtu_writer.cpp does (the self-check's planted files)."""
    payload = np.ascontiguousarray(values).tobytes()
    if not compressed:
        return base64.b64encode(np.uint64(len(payload)).tobytes() + payload).decode()
    blocks = [zlib.compress(payload[i:i + block], 1) for i in range(0, len(payload), block)]
    header = [len(blocks), block, len(payload) % block] + [len(b) for b in blocks]
    return (base64.b64encode(np.array(header, "<u8").tobytes()).decode() +
            base64.b64encode(b"".join(blocks)).decode())


def write_test_vtu(path, displacement, compressed):
    """A two-triangle VTU in roller's layout with the given 4 x 2 point data."""
    def array(vtk_type, name, values, nc=None):
        attrs = ' NumberOfComponents="%d"' % nc if nc else ""
        return '        <DataArray type="%s" Name="%s"%s format="binary">\n          %s\n        </DataArray>\n' % (
            vtk_type, name, attrs, encode_vtu_array(values, compressed))
    points = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], "<f8")
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian"'
                ' header_type="UInt64"%s>\n  <UnstructuredGrid>\n    <Piece NumberOfPoints="4" NumberOfCells="2">\n'
                % (' compressor="vtkZLibDataCompressor"' if compressed else ""))
        f.write("      <PointData>\n" + array("Float64", "displacement", np.asarray(displacement, "<f8"), 2) +
                "      </PointData>\n      <CellData>\n" + array("Float64", "stress", np.zeros((2, 4), "<f8"), 4) +
                "      </CellData>\n      <Points>\n" + array("Float64", "Points", points, 3) + "      </Points>\n"
                "      <Cells>\n" + array("Int64", "connectivity", np.array([0, 1, 2, 0, 2, 3], "<i8")) +
                array("Int64", "offsets", np.array([3, 6], "<i8")) + array("UInt8", "types", np.array([5, 5], "u1")) +
                "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n")


def scanner_self_check():
    """The scan must be able to fail: planted nan/inf values in a CSV, a JSON and VTU files
    (zlib-compressed and raw) are found, a clean VTU passes and a cut VTU array is malformed.
    Returns a list of what went wrong (empty when the scanner works)."""
    wrong = []
    with tempfile.TemporaryDirectory() as d:
        def check(name, expected_kind):
            kind, messages = scan_file(os.path.join(d, name))
            if kind != expected_kind:
                wrong.append("%s: scanned as %r (%s), expected %r" % (name, kind, "; ".join(messages), expected_kind))
        with open(os.path.join(d, "a.csv"), "w") as f:
            f.write("step,fx\n1,0.5\n2,-nan\n")
        check("a.csv", "nonfinite")
        with open(os.path.join(d, "b.json"), "w") as f:
            f.write('{"fx": null}\n')
        check("b.json", "nonfinite")
        u = np.arange(8.0).reshape(4, 2)
        for compressed in (True, False):
            tag = "z" if compressed else "raw"
            write_test_vtu(os.path.join(d, "clean_%s.vtu" % tag), u, compressed)
            check("clean_%s.vtu" % tag, "")
            for bad in (np.nan, -np.inf):
                v = u.copy()
                v[3, 1] = bad
                write_test_vtu(os.path.join(d, "bad_%s_%s.vtu" % (tag, bad)), v, compressed)
                check("bad_%s_%s.vtu" % (tag, bad), "nonfinite")
            write_test_vtu(os.path.join(d, "short_%s.vtu" % tag), u[:3], compressed)
            check("short_%s.vtu" % tag, "malformed")
    return wrong


# ---------------------------------------------------------------- running and judging

def roller_env():
    env = dict(os.environ)
    for k, v in SANITIZER_ENV.items():
        env.setdefault(k, v)
    return env


def run_case(roller, scene_path, extra, out_dir, timeout):
    cmd = [roller, "run", scene_path, "--out", out_dir, "--overwrite"] + extra
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True,
                         env=roller_env())
    try:
        output, _ = p.communicate(timeout=timeout)
        return cmd, p.returncode, output.decode(errors="replace"), False
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        output, _ = p.communicate()
        return cmd, None, output.decode(errors="replace"), True


def sanitizer_report(output):
    """The most telling line of a sanitizer report in the output (SUMMARY, else the first one)."""
    lines = [m.group(0).strip() for m in SANITIZER_REPORT.finditer(output)]
    if not lines:
        return ""
    summary = [line for line in lines if line.startswith("SUMMARY:")]
    line = re.sub(r"^==\d+==", "", (summary or lines)[0])
    return line[:200]


def describe(flagged, out_dir):
    return "; ".join("%s: %s" % (os.path.relpath(p, out_dir), ", ".join(m)) for _, p, m in flagged)[:400]


def verdict(rc, output, timed_out, out_dir):
    """(reason, flagged output files): reason "" when the case passed."""
    report = sanitizer_report(output)
    if report:
        return "sanitizer report (exit %s): %s" % ("timeout" if timed_out else rc, report), []
    if timed_out:
        return "hang (timeout)", []
    if rc is None or rc < 0 or rc >= 128:
        return "crash (signal %s)" % (-rc if rc is not None and rc < 0 else rc), []
    if "roller: internal error:" in output or "roller: error:" in output:
        tail = output.split("error:", 1)[-1].strip().splitlines()
        return "unexpected exception (exit %d): %s" % (rc, tail[0][:120] if tail else ""), []
    if rc == 2 and "input error" not in output and "Run with --help" not in output:
        return "exit 2 without an input-error message", []
    if rc == 1 and "error:" not in output:
        return "exit 1 without an error line", []
    if rc == 3 and "system error" not in output:
        return "exit 3 without a system-error message", []
    if rc not in (0, 1, 2, 3):
        return "undocumented exit code %d" % rc, []
    flagged = scan_outputs(out_dir)
    malformed = [f for f in flagged if f[0] == "malformed"]
    nonfinite = [f for f in flagged if f[0] == "nonfinite"]
    if malformed:
        return "malformed VTU after exit %d: %s" % (rc, describe(malformed, out_dir)), flagged
    if nonfinite and rc == 0:
        return "exit 0 (converged) but nan/inf in an output: %s" % describe(nonfinite, out_dir), flagged
    if nonfinite:
        return "nan/inf in an output after exit %d: %s" % (rc, describe(nonfinite, out_dir)), flagged
    return "", []


def save_failure(failures, case, scene_path, cmd, output, problem, what, seed, flagged, out_dir, sanitized):
    d = os.path.join(failures, "%04d" % case)
    os.makedirs(d)
    shutil.copy(scene_path, os.path.join(d, "scene.toml"))
    # The command as run, on the saved scene and into OUT/failures/<n>/out.
    cmd = [os.path.join(d, "scene.toml") if a == scene_path else os.path.join(d, "out") if a == out_dir else a
           for a in cmd]
    env = [k + "=" + roller_env()[k] for k in sorted(SANITIZER_ENV)] if sanitized else []
    with open(os.path.join(d, "command.txt"), "w") as f:
        f.write("# %s: %s (from problems/%s.toml)\n%s\n" % (problem, what, seed, shlex.join(env + cmd)))
    with open(os.path.join(d, "output.txt"), "w") as f:
        f.write(output)
    for _, path, _ in flagged:
        target = os.path.join(d, "outputs", os.path.relpath(path, out_dir))
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy(path, target)
    return d


def scan_command(paths):
    """--scan: print what the scanner sees in the given files or folders."""
    n_bad = 0
    files = []
    for p in paths:
        if os.path.isdir(p):
            files += [os.path.join(d, n) for d, _, names in sorted(os.walk(p)) for n in sorted(names)]
        else:
            files.append(p)
    for path in files:
        kind, messages = scan_file(path)
        if path.endswith(".vtu") and kind != "malformed":
            arrays = decode_vtu(path)
            print("%s: %d arrays" % (path, len(arrays)))
            for section, name, values in arrays:
                print("    %-9s %-24s %-8s %d x %d" % (section, name, values.dtype.name, *values.shape))
        elif not kind:
            print("%s: %s" % (path, "clean" if path.endswith(TEXT_OUTPUTS) else "not scanned"))
        if kind:
            n_bad += 1
            print("%s: %s: %s" % (path, "NAN/INF" if kind == "nonfinite" else "MALFORMED", "; ".join(messages)))
    return 1 if n_bad else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--roller", default=os.path.join(ROOT, "build", "roller"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "fuzz"))
    ap.add_argument("--timeout", type=float, default=30.0)
    ap.add_argument("--steps", type=int, default=None, help="steps per run (default 2, with --sanitized 1)")
    ap.add_argument("--sanitized", action="store_true",
                    help="ROLLER is a sanitizer build: smaller scenes, --steps 1, no --refine 2")
    ap.add_argument("--scan", nargs="+", metavar="PATH", help="only scan these output files or folders")
    args = ap.parse_args()
    if args.scan:
        return scan_command(args.scan)
    wrong = scanner_self_check()
    if wrong:
        print("fuzz: the output scanner misses planted values:\n    " + "\n    ".join(wrong))
        return 1
    SCANNED.update(files=0, vtu=0, arrays=0)
    steps = args.steps if args.steps is not None else (1 if args.sanitized else 2)
    seeds = SMALL_SEEDS if args.sanitized else SEEDS
    rng = random.Random(args.seed)
    keys = scene_keys(args.roller)
    work = os.path.join(args.out, "work")
    failures = os.path.join(args.out, "failures")
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(work)
    counts = {}
    n_failed = 0
    t0 = time.monotonic()
    for case in range(1, args.cases + 1):
        seed = rng.choice(seeds)
        with open(os.path.join(ROOT, "problems", seed + ".toml")) as f:
            text = f.read()
        extra, what = [], ""
        if rng.random() < 0.3:
            extra, what = set_override(keys, rng)
        else:
            text, what = mutate_text(text, rng)
        options, options_what = cli_options(rng, steps, args.sanitized)
        if options_what:
            what += ", " + options_what
        scene_path = os.path.join(work, "case.toml")
        with open(scene_path, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(text)
        out_dir = os.path.join(work, "out")
        cmd, rc, output, timed_out = run_case(args.roller, scene_path, options + extra, out_dir, args.timeout)
        problem, flagged = verdict(rc, output, timed_out, out_dir)
        key = "timeout" if timed_out else str(rc)
        counts[key] = counts.get(key, 0) + 1
        if problem:
            n_failed += 1
            d = save_failure(failures, case, scene_path, cmd, output, problem, what, seed, flagged, out_dir,
                             args.sanitized)
            print("case %4d FAILED %s: %s (problems/%s.toml) -> %s" % (case, problem, what, seed, d), flush=True)
        shutil.rmtree(out_dir, ignore_errors=True)
    print("fuzz: %d cases in %.0f s (seed %d%s), exit codes %s; %d output files scanned (%d VTU, %d arrays "
          "decoded); %d failed" % (
              args.cases, time.monotonic() - t0, args.seed, ", sanitized" if args.sanitized else "",
              ", ".join("%s: %d" % kv for kv in sorted(counts.items())), SCANNED["files"], SCANNED["vtu"],
              SCANNED["arrays"], n_failed))
    return 1 if n_failed else 0


if __name__ == "__main__":
    sys.exit(main())
