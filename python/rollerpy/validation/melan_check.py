"""Melan's bound against transient passes (docs/validation.md, "Melan's bound"): `roller
shakedown-limit` gives the scene's limit as a load factor lambda; the scene is then run with every
initial yield stress scaled so that its own load lies a fraction below and above the limit (the
limit scales with the yield stresses at a fixed load, which keeps the contact's shape), and the
passes' verdicts are compared: elastic shakedown below, none above.

usage: ./rollerpy melan-check SCENE [--margin 0.05] [--passes 8] [--out out/melan_check/NAME]
                              [--traction Q] [--roller ./build/roller] [--timeout 7200]

Writes OUT/limit.json (the shakedown-limit), OUT/below/ and OUT/above/ (the runs, with their
passes.png) and OUT/melan_check.md (the table); exit status 1 when a verdict disagrees.
"""
import json
import os
import sys
import tomllib

from ..command import parser
from ..outputs import read_rows, read_summary
from ..paths import ROOT
from ..plots import passes as plot_passes
from ..runner import run, set_options


def scaled_yield(scene_file, factor):
    """--set pairs that multiply every initial yield stress of the scene by `factor`."""
    with open(scene_file, "rb") as f:
        scene = tomllib.load(f)
    material = scene.get("material", {})
    if "yield_stress" not in material:
        sys.exit("melan-check: %s has no material.yield_stress" % scene_file)
    if any("yield_stress" in layer for layer in scene.get("layer", [])):
        sys.exit("melan-check: %s: [[layer]] blocks with their own yield_stress are not scaled yet" % scene_file)
    pairs = [("material.yield_stress", repr(material["yield_stress"] * factor))]
    if "yield_profile" in material:
        profile = ", ".join("[%r, %r]" % (z, s * factor) for z, s in material["yield_profile"])
        pairs.append(("material.yield_profile", "[%s]" % profile))
    return pairs


def mean_increments(out):
    return [float(r["mean_plastic_increment"]) for r in read_rows(os.path.join(out, "passes.csv"), missing_ok=True)]


def main(argv=None):
    ap = parser("melan-check", __doc__)
    ap.add_argument("scene")
    ap.add_argument("--margin", type=float, default=0.05, help="below and above the limit by this fraction")
    ap.add_argument("--passes", type=int, default=8)
    ap.add_argument("--traction", type=float, default=None, help="q/p (default: the scene's)")
    ap.add_argument("--out", default=None)
    ap.add_argument("--roller", default="./build/roller")
    ap.add_argument("--timeout", type=float, default=7200.0)
    args = ap.parse_args(argv)
    os.chdir(ROOT)
    roller = os.path.abspath(args.roller)
    name = os.path.splitext(os.path.basename(args.scene))[0]
    out = args.out or os.path.join("out", "melan_check", name)
    os.makedirs(out, exist_ok=True)
    limit_file = os.path.join(out, "limit.json")
    cmd = [roller, "shakedown-limit", args.scene, "--json", limit_file]
    if args.traction is not None:
        cmd += ["--traction", str(args.traction)]
    if run(cmd, os.path.join(out, "limit.log"), args.timeout).exit_code != 0:
        sys.exit("melan-check: shakedown-limit failed (%s)" % os.path.join(out, "limit.log"))
    with open(limit_file) as f:
        limit = json.load(f)
    factor = limit["elastic"]["load_factor"]
    p0k = limit["elastic"]["p0_over_k"]
    print("melan-check: %s: Melan's limit at load factor %.4f (p0/k = %.4f)" % (name, factor, p0k))
    rows, agree = [], True
    for side, fraction, expected in (("below", 1.0 - args.margin, True), ("above", 1.0 + args.margin, False)):
        # The scene's load at `fraction` of the limit: the yield stresses over fraction * factor.
        pairs = scaled_yield(args.scene, 1.0 / (fraction * factor)) + [("passes.count", str(args.passes))]
        if args.traction is not None:
            pairs.append(("contact.friction", repr(args.traction)))
        run_out = os.path.join(out, side)
        result = run([roller, "run", args.scene, "--out", run_out, "--overwrite"] + set_options(pairs),
                     run_out + ".log", args.timeout)
        summary = read_summary(run_out, missing_ok=True) or {}
        verdict = summary.get("passes", {}).get("verdict", "failed (exit %s)" % result.exit_code)
        increments = mean_increments(run_out)
        ok = (verdict == "elastic_shakedown") == expected and result.exit_code == 0
        agree = agree and ok
        rows.append((side, fraction * limit["elastic"]["p0_over_k"], verdict, increments, result.wall_s, ok))
        print("  %s: p0/k = %.3f -> %s, mean increments %s (%.0f s)%s" % (
            side, rows[-1][1], verdict, " ".join("%.3g" % v for v in increments), result.wall_s,
            "" if ok else "  <- disagrees with Melan"))
        if increments:
            plot_passes.plot(run_out)
    with open(os.path.join(out, "melan_check.md"), "w") as f:
        f.write("| side | p0/k | verdict | mean increments per pass | run [s] |\n|---|---|---|---|---|\n")
        for side, p0k, verdict, inc, wall, ok in rows:
            f.write("| %s | %.3f | %s | %s | %.0f |\n" % (side, p0k, verdict, " ".join("%.3g" % v for v in inc), wall))
    return 0 if agree else 1
