#!/usr/bin/python3
"""Every shipped scene, run in full with both contact backends: each run must end with exit
code 0 and no output file may hold nan or inf (CTest "outputs of every shipped scene",
label slow; docs/stability.md, "No nan or inf in any output").

usage: /usr/bin/python3 scripts/check_scene_outputs.py [--out build/scene_outputs]
                                                       [--roller ./build/roller] [--timeout 900]
                                                       [--only z1_outf05,hertz]

problems/z3_data02.toml starts from z3_data01's final state of the same backend. The shakedown
scenes (problems/shakedown_p*.toml, minutes each) are skipped unless --only names them; their
study (scripts/shakedown.py) scans its own outputs. Files scanned:
every CSV cell, JSON value, VTU DataArray, CBOR float and nan/inf token of the text files and of
the log (scripts/stability.py, scan_outputs). Prints one line per run; exit code 1 if any run
failed or wrote a non-finite number.
"""
import argparse
import glob
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from stability import run_one, scan_file, scan_outputs  # noqa: E402


def scanner_sees_planted_values():
    """The scan must be able to fail: a nan cell, an inf cell and a JSON null are each found."""
    with tempfile.TemporaryDirectory() as d:
        planted = {"a.csv": "step,fx\n1,0.5\n2,nan\n", "b.csv": "step,fx\n1,-inf\n", "c.json": '{"fx": null}'}
        for name, text in planted.items():
            with open(os.path.join(d, name), "w") as f:
                f.write(text)
        return all(scan_file(os.path.join(d, name)) == 1 for name in planted)


def has_roller(scene):
    with open(scene) as f:
        return any(line.strip() == "[roller]" for line in f)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="build/scene_outputs")
    ap.add_argument("--roller", default="./build/roller")
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--only", default="", help="comma-separated scene names")
    args = ap.parse_args()
    os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    if not scanner_sees_planted_values():
        print("the output scanner misses planted nan/inf values")
        return 1
    roller = os.path.abspath(args.roller)
    only = set(filter(None, args.only.split(",")))
    os.makedirs(args.out, exist_ok=True)
    scenes = sorted(glob.glob("problems/*.toml"))  # z3_data01 before z3_data02
    failures = []
    for scene in scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        if only and name not in only:
            continue
        if not only and name.startswith("shakedown_"):
            continue
        for backend in (["ipopt", "penalty"] if has_roller(scene) else [None]):
            out = os.path.join(args.out, "%s_%s" % (name, backend) if backend else name)
            log = out + ".log"
            extra = []
            if name == "z3_data02":
                extra = ["--initial-state", os.path.join(args.out, "z3_data01_%s" % backend, "state_final.cbor")]
            _, rc, timed_out, wall = run_one(roller, scene, extra, backend, out, log, args.timeout)
            n_files, problems = scan_outputs(out, log)
            ok = rc == 0 and not problems
            print("%-22s %-8s %s exit %s, %3d files scanned, %d with nan/inf, %.1f s" % (
                name, backend or "-", "ok    " if ok else "FAILED", "timeout" if timed_out else rc, n_files,
                len(problems), wall), flush=True)
            for p in problems:
                print("    " + p)
            if not ok:
                failures.append("%s %s" % (name, backend or ""))
    if failures:
        print("failed: " + ", ".join(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
