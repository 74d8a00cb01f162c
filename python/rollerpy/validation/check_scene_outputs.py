"""Every shipped scene, run in full with both contact backends: each run must end with exit
code 0 and no output file may hold nan or inf (CTest "outputs of problems/<scene>.toml", one test
per scene, label slow; the penalty backend's runs of burnishing and carter, ~3 min each, label long;
docs/stability.md, "No nan or inf in any output").

usage: ./rollerpy check-scene-outputs [--out build/scene_outputs]
                                     [--roller ./build/roller] [--timeout 900]
                                     [--only z1_outf05,hertz] [--backends ipopt,penalty]

problems/z3_data02.toml starts from z3_data01's final state of the same backend. The shakedown
scenes (problems/shakedown_p*.toml, minutes each) are skipped unless --only names them; their
study (`rollerpy shakedown`) scans its own outputs. Files scanned:
every CSV cell, JSON value, VTU DataArray, CBOR float and nan/inf token of the text files and of
the log (rollerpy.scan). Prints one line per run; exit code 1 if any run failed or wrote a
non-finite number.
"""
import glob
import os

from ..command import parser
from ..paths import ROOT
from ..scan import scan_outputs, self_check
from .stability import run_one


def has_roller(scene):
    with open(scene) as f:
        return any(line.strip() == "[roller]" for line in f)


def main(argv=None):
    ap = parser("check-scene-outputs", __doc__)
    ap.add_argument("--out", default="build/scene_outputs")
    ap.add_argument("--roller", default="./build/roller")
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--only", default="", help="comma-separated scene names")
    ap.add_argument("--backends", default="ipopt,penalty",
                    help="comma-separated backends for the scenes with a roller (ipopt, penalty)")
    args = ap.parse_args(argv)
    os.chdir(ROOT)  # relative paths (the defaults too) are the checkout's
    roller, out_root = os.path.abspath(args.roller), os.path.abspath(args.out)
    wrong = self_check()
    if wrong:
        print("the output scanner misses planted nan/inf values:\n    " + "\n    ".join(wrong))
        return 1
    only = set(filter(None, args.only.split(",")))
    backends = [b for b in args.backends.split(",") if b]
    if not backends or set(backends) - {"ipopt", "penalty"}:
        print("--backends %s: expected ipopt, penalty or both, comma-separated" % args.backends)
        return 2
    os.makedirs(out_root, exist_ok=True)
    scenes = sorted(glob.glob("problems/*.toml"))  # z3_data01 before z3_data02
    unknown = only - {os.path.splitext(os.path.basename(s))[0] for s in scenes}
    if unknown:
        print("--only names no scene in problems/: " + ", ".join(sorted(unknown)))
        return 2
    failures = []
    for scene in scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        if only and name not in only:
            continue
        if not only and name.startswith("shakedown_"):
            continue
        for backend in (backends if has_roller(scene) else [None]):
            out = os.path.join(out_root, "%s_%s" % (name, backend) if backend else name)
            log = out + ".log"
            extra = []
            if name == "z3_data02":
                extra = ["--initial-state", os.path.join(out_root, "z3_data01_%s" % backend, "state_final.cbor")]
            result = run_one(roller, scene, extra, backend, out, log, args.timeout)
            scan = scan_outputs(out, log)
            n_files, problems = scan.files, scan.problems(out)
            ok = result.exit_code == 0 and not problems
            print("%-22s %-8s %s exit %s, %3d files scanned, %d with nan/inf, %.1f s" % (
                name, backend or "-", "ok    " if ok else "FAILED", "timeout" if result.timed_out else result.exit_code,
                n_files, len(problems), result.wall_s), flush=True)
            for p in problems:
                print("    " + p)
            if not ok:
                failures.append("%s %s" % (name, backend or ""))
    if failures:
        print("failed: " + ", ".join(failures))
        return 1
    return 0
