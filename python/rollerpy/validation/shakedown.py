"""Shakedown of a rolling line contact against Johnson's results (docs/validation.md,
"Shakedown: repeated rolling of a line contact").

usage: ./rollerpy shakedown [--out out/shakedown] [--backends ipopt,penalty]
                           [--loads 30,37,45,55] [--roller ./build/roller]
                           [--timeout 3600] [--passes N] [--no-run]

1. First yield: problems/shakedown_p30.toml pressed to its load (steps 1-3, one pass; 3.0 k is
   below Johnson's 3.1 k, so the strip stays elastic); the largest element von Mises stress
   sigma_vm gives the load of first yield p0/k = 3.0 sigma_y / sigma_vm (the elastic stresses
   scale with p0 at a fixed shape of the pressure).
2. The four scenes problems/shakedown_pXX.toml (5 passes each) with every backend: the verdict of
   summary.json and the per-pass increments of passes.csv.
Writes OUT/shakedown.csv (one row per scene and backend), OUT/table.md and OUT/shakedown.png
(the mean increment of equivalent plastic strain in the track against the pass, one curve per
load and backend), keeps every run in OUT/<scene>_<backend>/ with its passes.png and
residual_depth.png (`rollerpy plot-passes`), and checks every output file for nan/inf.
"""
import csv
import os

import numpy as np

from ..command import parser
from ..outputs import num, read_rows, read_scene, read_summary
from ..paths import ROOT
from ..plots import passes as plot_passes
from ..plots import plt
from ..scan import scan_outputs
from ..vtu import read_vtu
from .stability import run_one
JOHNSON_FIRST_YIELD = 3.1
JOHNSON_SHAKEDOWN = 4.0


def first_yield(args):
    out = os.path.join(args.out, "first_yield")
    log = out + ".log"
    extra = ["--set", "passes.count=1", "--steps", "3", "--set", "output.every=1", "--overwrite"]
    if run_one(args.roller, "problems/shakedown_p30.toml", extra, "ipopt", out, log, args.timeout).exit_code != 0:
        return None, None
    cells = read_vtu(os.path.join(out, "step_0003.vtu")).cell_data
    sigma_y = read_scene(out)["material"]["yield_stress"]
    vm = float(np.max(cells["von_mises"]))
    return 3.0 * sigma_y / vm, vm


def main(argv=None):
    ap = parser("shakedown", __doc__)
    ap.add_argument("--out", default="out/shakedown")
    ap.add_argument("--backends", default="ipopt,penalty")
    ap.add_argument("--loads", default="30,37,45,55")
    ap.add_argument("--roller", default="./build/roller")
    ap.add_argument("--timeout", type=float, default=3600.0)
    ap.add_argument("--passes", type=int, default=0, help="passes per scene (default: the scenes' 5)")
    ap.add_argument("--no-run", action="store_true", help="measure the runs already in --out")
    args = ap.parse_args(argv)
    os.chdir(ROOT)
    args.roller = os.path.abspath(args.roller)
    os.makedirs(args.out, exist_ok=True)
    rows, problems_total = [], 0
    yield_ratio, vm = first_yield(args)  # seconds: run even with --no-run
    for load in args.loads.split(","):
        scene = "problems/shakedown_p%s.toml" % load
        for backend in args.backends.split(","):
            out = os.path.join(args.out, "shakedown_p%s_%s" % (load, backend))
            log = out + ".log"
            wall = None
            if not args.no_run:
                extra = ["--overwrite"] + (["--set", "passes.count=%d" % args.passes] if args.passes else [])
                wall = run_one(args.roller, scene, extra, backend, out, log, args.timeout).wall_s
            summary = read_summary(out) if os.path.exists(os.path.join(out, "summary.json")) else {}
            passes = read_rows(os.path.join(out, "passes.csv"), missing_ok=True)
            problems = scan_outputs(out, log).flagged
            problems_total += len(problems)
            if passes:
                try:
                    plot_passes.plot(out)
                except (OSError, ValueError, KeyError) as e:  # a run cut short: its tables incomplete
                    print("shakedown: no figures of %s: %s" % (out, e))
            p = summary.get("passes", {})
            rows.append({
                "load": int(load) / 10.0, "backend": backend,
                "p0_over_k": "%.3f" % p["p0_over_k"] if "p0_over_k" in p else "",
                "converged": summary.get("converged", False), "verdict": p.get("verdict", "—"),
                "mean_dep": " ".join("%.2e" % num(r["mean_plastic_increment"]) for r in passes),
                "last_over_first": "%.3g" % (num(passes[-1]["mean_plastic_increment"]) /
                                             num(passes[0]["mean_plastic_increment"]))
                if passes and num(passes[0]["mean_plastic_increment"]) > 0 else "—",
                "net_share": p.get("criterion", ""),
                "wall_s": "%.0f" % summary.get("wall_s", wall or 0.0),
                "nonfinite": len(problems),
            })
            print("p0/k %s %-8s %-18s %s s" % (rows[-1]["load"], backend, rows[-1]["verdict"], rows[-1]["wall_s"]),
                  flush=True)
    with open(os.path.join(args.out, "shakedown.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    # The curves.
    fig, ax = plt.subplots(figsize=(7, 4.5))
    styles = {"ipopt": "-", "penalty": "--"}
    for r in rows:
        values = [float(v) for v in r["mean_dep"].split()] if r["mean_dep"] else []
        if not values:
            continue
        ax.semilogy(range(1, len(values) + 1), [v if v > 0 else np.nan for v in values], styles.get(r["backend"], ":"),
                    marker="o", label="p0/k = %.1f, %s: %s" % (r["load"], r["backend"], r["verdict"].replace("_", " ")))
    ax.set_xlabel("pass")
    ax.set_ylabel("mean increment of equivalent plastic strain in the track")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    ax.set_title("Frictionless rolling, elastic-perfectly plastic strip (Johnson: shakedown limit p0/k = 4.0)",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "shakedown.png"), dpi=150)
    with open(os.path.join(args.out, "table.md"), "w") as f:
        if yield_ratio:
            f.write("First yield: p0/k = %.3f (Johnson %.1f: %+.1f %%), largest von Mises %.1f MPa at p0/k = 3.0\n\n"
                    % (yield_ratio, JOHNSON_FIRST_YIELD, 100 * (yield_ratio / JOHNSON_FIRST_YIELD - 1), vm))
        f.write("| p0/k | backend | verdict | mean Δε̄ᵖ per pass | last / first | run [s] |\n"
                "|---|---|---|---|---|---|\n")
        for r in rows:
            f.write("| %s | %s | %s | %s | %s | %s |\n" % (
                r["load"], r["backend"], r["verdict"], r["mean_dep"], r["last_over_first"], r["wall_s"]))
        f.write("\nnon-finite values in the outputs: %d\n" % problems_total)
    print(open(os.path.join(args.out, "table.md")).read())
    return 0 if problems_total == 0 else 1
