#!/usr/bin/python3
"""Error against run time, penalty vs interior point (issue 7; docs/benchmarks.md).

usage: /usr/bin/python3 benchmarks/error_vs_time.py [--quick] [--build build] [--out DIR]
                                                      [--scenes hertz,cattaneo,...] [--check]

Runs build/benchmarks/bench_error_time (sweeps of mesh refinement, penalty factor and Ipopt
tolerance for each scene, timed, errors against a reference), then draws one log-log PNG per
scene and error measure (error against wall time, one curve per backend and swept parameter,
the Pareto front marked) into DIR (default out/error_vs_time). --check validates the CSV
(columns present, errors of converged runs finite, the finer Hertz mesh has the smaller
pressure error) and exits non-zero when it is not sane.
"""
import argparse
import csv
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLUMNS = ["scene", "backend", "parameter", "value", "refine", "dofs", "converged", "wall_s", "repeats",
           "iterations", "factorizations", "residual", "max_penetration", "force_error",
           "pressure_l2_error", "sqrt_i2_error", "tau_xx_error", "reference"]
ERRORS = {"pressure_l2_error": "pressure-profile L2 error", "force_error": "contact-force error",
          "sqrt_i2_error": "sqrt(I2) field error", "tau_xx_error": "tau_xx field error"}
STYLE = {("penalty", "refine"): ("tab:red", "o-"), ("ipopt", "refine"): ("tab:blue", "s-"),
         ("penalty", "penalty_factor"): ("tab:orange", "^--"), ("ipopt", "ipopt_tol"): ("tab:cyan", "v--")}


def pareto(points):
    """Points (t, e) not dominated by another (less time and less error)."""
    front, best = [], math.inf
    for t, e in sorted(points):
        if e < best:
            front.append((t, e))
            best = e
    return front


def plot(rows, out_dir):
    written = []
    for scene in dict.fromkeys(r["scene"] for r in rows):
        for key, label in ERRORS.items():
            sel = [r for r in rows if r["scene"] == scene and r["converged"] == "1"]
            pts = [(float(r["wall_s"]), float(r[key])) for r in sel]
            pts = [(t, e) for t, e in pts if math.isfinite(e) and e > 0]
            if len(pts) < 2:
                continue
            fig, ax = plt.subplots(figsize=(6.4, 4.6))
            for (backend, param), (color, fmt) in STYLE.items():
                curve = [r for r in sel if r["backend"] == backend and r["parameter"] == param]
                xy = [(float(r["wall_s"]), float(r[key]), r["value"]) for r in curve]
                xy = [p for p in xy if math.isfinite(p[1]) and p[1] > 0]
                if not xy:
                    continue
                ax.plot([p[0] for p in xy], [p[1] for p in xy], fmt, color=color,
                        label=f"{backend}: {param.replace('_', ' ')}")
                for t, e, v in xy:
                    ax.annotate(f"{float(v):g}", (t, e), fontsize=6, xytext=(3, 3), textcoords="offset points")
            front = pareto(pts)
            ax.plot([p[0] for p in front], [p[1] for p in front], color="k", lw=2.5, alpha=0.25,
                    label="Pareto front")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("wall time per run [s]")
            ax.set_ylabel(label)
            ax.set_title(f"{scene}: {label} against run time")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
            path = os.path.join(out_dir, f"{scene}_{key}.png")
            fig.tight_layout()
            fig.savefig(path, dpi=120)
            plt.close(fig)
            written.append(path)
    return written


def check(rows):
    problems = []
    if not rows:
        return ["no rows"]
    missing = [c for c in COLUMNS if c not in rows[0]]
    if missing:
        problems.append(f"missing columns {missing}")
    for r in rows:
        if r["converged"] != "1":
            problems.append(f"run did not converge: {r['scene']} {r['backend']} {r['parameter']}={r['value']}")
            continue
        for key in list(ERRORS) + ["wall_s", "residual", "max_penetration"]:
            v = float(r[key])
            if not math.isfinite(v) or v < 0:
                problems.append(f"{key} = {r[key]} not finite/non-negative in {r['scene']} {r['backend']} "
                                f"{r['parameter']}={r['value']}")
    for backend in ("penalty", "ipopt"):
        h = sorted((int(r["refine"]), float(r["pressure_l2_error"])) for r in rows
                   if r["scene"] == "hertz" and r["backend"] == backend and r["parameter"] == "refine")
        if len(h) < 2:
            problems.append(f"hertz/{backend}: fewer than two mesh levels")
        elif not all(b[1] < a[1] for a, b in zip(h, h[1:])):
            problems.append(f"hertz/{backend}: the pressure error does not fall with refinement: {h}")
    return problems


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="out/error_vs_time")
    ap.add_argument("--scenes", default="")
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    csv_path = os.path.join(args.out, "error_vs_time.csv")
    cmd = [os.path.join(args.build, "benchmarks", "bench_error_time"), "--out", csv_path]
    if args.quick:
        cmd.append("--quick")
    if args.scenes:
        cmd += ["--scenes", args.scenes]
    print("running:", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    for path in plot(rows, args.out):
        print("wrote", path)
    print("wrote", csv_path)
    if args.check:
        problems = check(rows)
        for p in problems:
            print("check failed:", p, file=sys.stderr)
        if problems:
            return 1
        print("check passed:", len(rows), "runs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
