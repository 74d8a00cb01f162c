"""Error against run time, penalty vs interior point (docs/benchmarks.md).

usage: ./rollerpy bench-error-vs-time [--quick] [--build DIR] [--out DIR]
           [--scenes hertz,cattaneo,...] [--refine-max N] [--max-run-seconds S]
           [--max-reference-seconds S] [--plot-only] [--check] [--jobs N] [--scheduler ADDR] [--resume]

Runs DIR/benchmarks/bench_error_time (default DIR: build/ of this checkout; when the program is
missing it is built first: `bash scripts/build.sh` for build/, a CMake build of the one target
otherwise), once per scene, as points of the study runner (rollerpy.study): one scene at a time
by default (timings undisturbed), --jobs N side by side on a Dask LocalCluster or --scheduler on
a cluster; --resume keeps the scenes already complete in --out (OUT/scenes/SCENE/). The program
sweeps mesh refinement, penalty factor and Ipopt tolerance for each
scene, times every run and compares it with a reference run (ipopt, one mesh level finer, the
tightest tolerance; Hertz pressure: the analytic solution). Every run is guarded: a failure, an
exception or the per-run budget (--max-run-seconds, stopped between steps) ends that run only
and is recorded as a row with status failed / error / timeout (later, costlier runs of the same
sweep: skipped). Then one log-log PNG per scene and measure is drawn into --out (default
out/error_vs_time): error, max penetration or equilibrium residual against wall time, one curve
per backend and swept parameter, the Pareto front marked; only converged runs are drawn; plus
SCENE_overview.png (all six panels of a scene) and tables.md (the CSV as Markdown tables). At the
end: which error is against what, and the wall time spent per scene.
--plot-only redraws from an existing CSV. --check validates the CSV (columns present, every
run converged, errors of converged runs finite, the finer Hertz mesh has the smaller pressure
error) and exits non-zero when it is not sane.
"""
import csv
import math
import os
import subprocess
import sys
import time

from ..command import parser
from ..outputs import num as fnum
from ..outputs import read_rows
from ..paths import ROOT as REPO
from ..plots import plt
from ..study import engines
from ..study.point import finished_record, make_task, run_point
# The plan's scenes (bench_error_time.cpp, plans()), in its order.
SCENES = ["hertz", "cattaneo", "z1_outf05", "z3_data01", "z4_v25"]
QUICK_SCENES = ["hertz", "cattaneo"]
STUDY_BUDGET_S = 3600.0  # the default study should fit in one hour on 2 cores

COLUMNS = ["scene", "backend", "parameter", "value", "refine", "dofs", "status", "converged", "message",
           "wall_s", "repeats", "cost_s", "steps", "steps_done", "iterations", "factorizations", "residual_max",
           "residual_last", "max_penetration", "load_step", "force_error", "pressure_l2_error",
           "pressure_reference", "final_roller_force", "final_contact_nodes", "final_state",
           "final_sqrt_i2_error", "final_tau_xx_error", "reference_backend", "reference_refine",
           "reference_tol", "errors_against"]
# Measures compared with the reference (error_vs_time.csv column -> label).
ERRORS = {"pressure_l2_error": "pressure-profile L2 error (load step)",
          "force_error": "roller-force error (load step)",
          "final_sqrt_i2_error": "final-step sqrt(I2) field error",
          "final_tau_xx_error": "final-step tau_xx field error"}
# Measures of the run itself.
MEASURES = {"max_penetration": "max penetration over all steps [mm]",
            "residual_max": "max relative equilibrium residual over all steps"}
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


def reference_row(rows, scene):
    return next((r for r in rows if r["scene"] == scene and r["parameter"] == "reference"), None)


def describe_final(rows, scene):
    ref = reference_row(rows, scene)
    if ref is None or not ref.get("final_state"):
        return ""
    return ("roller lifted off: residual fields" if ref["final_state"] == "unloaded"
            else "roller still loaded")


def draw_panel(ax, rows, scene, key, label, small=False):
    """One log-log panel of `key` against wall time for `scene`; False when there is nothing to draw."""
    sel = [r for r in rows if r["scene"] == scene and r["status"] == "converged" and r["parameter"] != "reference"]
    raw = [(fnum(r["wall_s"]), fnum(r[key])) for r in sel]
    raw = [(t, e) for t, e in raw if t > 0 and math.isfinite(e) and e >= 0]
    positive = [e for _, e in raw if e > 0]
    if len(raw) < 2 or not positive:
        return False
    # Exact zeros (ipopt's penetration) cannot sit on a log axis: drawn on a floor line.
    floor = min(positive) / 10.0
    has_zero = any(e == 0 for _, e in raw)
    for (backend, param), (color, fmt) in STYLE.items():
        curve = [r for r in sel if r["backend"] == backend and r["parameter"] == param]
        xy = [(fnum(r["wall_s"]), fnum(r[key]), r["value"]) for r in curve]
        xy = [(t, e if e > 0 else floor, v) for t, e, v in xy if t > 0 and math.isfinite(e) and e >= 0]
        if not xy:
            continue
        ax.plot([p[0] for p in xy], [p[1] for p in xy], fmt, color=color, label=f"{backend}: {param.replace('_', ' ')}")
        for t, e, v in xy:
            ax.annotate(f"{float(v):g}", (t, e), fontsize=5 if small else 6, xytext=(3, 3), textcoords="offset points")
    front = pareto([(t, e if e > 0 else floor) for t, e in raw])
    ax.plot([p[0] for p in front], [p[1] for p in front], color="k", lw=2.5, alpha=0.25, label="Pareto front")
    if has_zero:
        ax.axhline(floor, color="gray", ls=":", lw=1, label="exactly 0 (drawn here)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per run [s]")
    ax.set_ylabel(label, fontsize=7 if small else None)
    title = label if small else f"{scene}: {label}"
    if key.startswith("final_"):
        final = describe_final(rows, scene)
        if final:
            title += f"\n({final})"
    ax.set_title(title, fontsize=8 if small else 10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=5 if small else 7)
    return True


def plot(rows, out_dir):
    """One PNG per scene and measure, and one overview per scene with all its panels."""
    written = []
    panels = list(ERRORS.items()) + list(MEASURES.items())
    for scene in dict.fromkeys(r["scene"] for r in rows):
        for key, label in panels:
            fig, ax = plt.subplots(figsize=(6.4, 4.6))
            if draw_panel(ax, rows, scene, key, label):
                path = os.path.join(out_dir, f"{scene}_{key}.png")
                fig.tight_layout()
                fig.savefig(path, dpi=120)
                written.append(path)
            plt.close(fig)
        fig, axes = plt.subplots(2, 3, figsize=(15, 8.4))
        drawn = [draw_panel(ax, rows, scene, key, label, small=True) for ax, (key, label) in zip(axes.flat, panels)]
        for ax, ok in zip(axes.flat, drawn):
            ax.set_visible(ok)
        if any(drawn):
            fig.suptitle(f"{scene}: error against wall time, penalty vs interior point", fontsize=12)
            fig.tight_layout()
            path = os.path.join(out_dir, f"{scene}_overview.png")
            fig.savefig(path, dpi=100)
            written.append(path)
        plt.close(fig)
    return written


def markdown_tables(rows):
    """The CSV as one Markdown table per scene (for docs/benchmarks.md)."""
    def g(v):
        x = fnum(v)
        return "–" if not math.isfinite(x) else f"{x:.2e}"
    lines = []
    for scene in dict.fromkeys(r["scene"] for r in rows):
        ref = reference_row(rows, scene)
        lines.append(f"\n**{scene}** (reference: {ref['errors_against'] if ref else 'none'})\n")
        lines.append("| backend | swept | value | refine | dofs | status | wall [s] | iterations | factorisations | "
                     "max pen. [mm] | max resid. | force err. | pressure L2 | √I2 err. | τxx err. |")
        lines.append("|---|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
        for r in rows:
            if r["scene"] != scene:
                continue
            lines.append(f"| {r['backend']} | {r['parameter']} | {fnum(r['value']):g} | {r['refine']} | {r['dofs']} | "
                         f"{r['status']} | {fnum(r['wall_s']):.2f} | {r['iterations']} | {r['factorizations']} | "
                         f"{g(r['max_penetration'])} | {g(r['residual_max'])} | {g(r['force_error'])} | "
                         f"{g(r['pressure_l2_error'])} | {g(r['final_sqrt_i2_error'])} | "
                         f"{g(r['final_tau_xx_error'])} |")
    return "\n".join(lines) + "\n"


def check(rows):
    problems = []
    if not rows:
        return ["no rows"]
    missing = [c for c in COLUMNS if c not in rows[0]]
    if missing:
        return [f"missing columns {missing}"]
    for r in rows:
        name = f"{r['scene']} {r['backend']} {r['parameter']}={r['value']} refine {r['refine']}"
        if r["status"] != "converged":
            problems.append(f"run {r['status']}: {name}: {r['message']}")
            continue
        keys = ["wall_s", "residual_max", "residual_last", "max_penetration"]
        if r["parameter"] != "reference":
            keys += list(ERRORS)
        for key in keys:
            v = fnum(r[key])
            if not math.isfinite(v) or v < 0:
                problems.append(f"{key} = {r[key]} not finite/non-negative in {name}")
        if int(r["factorizations"]) <= 0:
            problems.append(f"no factorisations recorded in {name}")
    for backend in ("penalty", "ipopt") if any(r["scene"] == "hertz" for r in rows) else ():
        h = sorted((int(r["refine"]), fnum(r["pressure_l2_error"])) for r in rows
                   if r["scene"] == "hertz" and r["backend"] == backend and r["parameter"] == "refine")
        if len(h) < 2:
            problems.append(f"hertz/{backend}: fewer than two mesh levels")
        elif not all(b[1] < a[1] for a, b in zip(h, h[1:])):
            problems.append(f"hertz/{backend}: the pressure error does not fall with refinement: {h}")
    return problems


def summary(rows, default_study, elapsed):
    print("\nerrors against (per scene):")
    for scene in dict.fromkeys(r["scene"] for r in rows):
        ref = reference_row(rows, scene)
        if ref is None:
            continue
        final = describe_final(rows, scene) or "reference did not finish"
        print(f"  {scene}: {ref['errors_against']}; force and pressure at step {ref['load_step']} of "
              f"{ref['steps']}, fields at the final step ({final})")
    print("\nwall time per scene [s] (cost = all repeats, loading and post-processing):")
    print(f"  {'scene':<12} {'reference':>10} {'sweeps':>9} {'total':>9}  runs: conv/failed/error/timeout/skipped")
    total = 0.0
    for scene in dict.fromkeys(r["scene"] for r in rows):
        sr = [r for r in rows if r["scene"] == scene]
        ref = sum(fnum(r["cost_s"]) for r in sr if r["parameter"] == "reference")
        sweeps = sum(fnum(r["cost_s"]) for r in sr if r["parameter"] != "reference")
        counts = [sum(1 for r in sr if r["status"] == s and r["parameter"] != "reference")
                  for s in ("converged", "failed", "error", "timeout", "skipped")]
        total += ref + sweeps
        print(f"  {scene:<12} {ref:10.1f} {sweeps:9.1f} {ref + sweeps:9.1f}  {'/'.join(map(str, counts))}")
    print(f"  {'all':<12} {'':>10} {'':>9} {total:9.1f}  "
          f"({total / 60:.1f} min; the program ran {elapsed / 60:.1f} min)")
    if default_study:
        verdict = "fits" if elapsed <= STUDY_BUDGET_S else "does NOT fit"
        print(f"default study: {elapsed / 60:.1f} min, {verdict} in the {STUDY_BUDGET_S / 60:.0f}-minute budget")
    else:
        print("(a selection, not the default study: the time above is for this selection only)")


def ensure_binary(build, bench):
    if os.path.isfile(bench) and os.access(bench, os.X_OK):
        return
    if os.path.realpath(build) == os.path.realpath(os.path.join(REPO, "build")):
        print(f"{bench} not found: building roller with `bash scripts/build.sh` (configures and builds build/; "
              "several minutes on 2 cores)", flush=True)
        subprocess.run(["bash", os.path.join(REPO, "scripts", "build.sh")], cwd=REPO, check=True)
    else:
        print(f"{bench} not found: configuring and building the target bench_error_time in {build}", flush=True)
        if not os.path.isfile(os.path.join(build, "CMakeCache.txt")):
            subprocess.run(["cmake", "-S", REPO, "-B", build, "-DCMAKE_BUILD_TYPE=Release"], check=True)
        subprocess.run(["cmake", "--build", build, "--target", "bench_error_time", "-j", str(os.cpu_count() or 1)],
                       check=True)
    if not os.path.isfile(bench):
        sys.exit(f"error: the build finished but {bench} is still missing")


def run_scenes(args, bench, csv_path):
    """One point of the study runner (rollerpy.study, docs/studies.md) per scene: each runs
    bench_error_time on that scene alone (its sweeps and its own reference) into
    OUT/scenes/SCENE/; serial by default so that timings are not disturbed, --jobs N on a
    LocalCluster or --scheduler on a cluster; --resume keeps the scenes complete. The scenes'
    CSVs are then joined into csv_path in the plan's order. Returns 0 when every scene finished."""
    scenes = args.scenes.split(",") if args.scenes else (QUICK_SCENES if args.quick else SCENES)
    tasks, records = [], []
    for i, scene in enumerate(scenes):
        out = os.path.abspath(os.path.join(args.out, "scenes", scene))
        cmd = [bench, "--out", os.path.join(out, "error_vs_time.csv"), "--scenes", scene]
        cmd += ["--quick"] if args.quick else []
        cmd += ["--refine-max", str(args.refine_max)] if args.refine_max else []
        if args.max_run_seconds is not None:
            cmd += ["--max-run-seconds", str(args.max_run_seconds)]
        if args.max_reference_seconds is not None:
            cmd += ["--max-reference-seconds", str(args.max_reference_seconds)]
        task = make_task(i, scene, cmd, out, values={"scene": scene})
        done = finished_record(out, task) if args.resume else None
        (records.append(done) if done else tasks.append(task))

    def on_done(record):
        records.append(record)
        print("%s: %s in %.0f s (%s)" % (record["name"], record["status"], record["wall_s"], record["message"]),
              flush=True)

    print("error_vs_time: %d scenes (%d complete) -> %s" % (len(scenes), len(records), csv_path), flush=True)
    if args.jobs == 1 and not args.scheduler:
        engines.run_serial(tasks, run_point, on_done)
    else:
        engines.run_dask(tasks, run_point, on_done, jobs=args.jobs, scheduler=args.scheduler)
    header, rows = None, []
    for scene in scenes:
        path = os.path.join(args.out, "scenes", scene, "error_vs_time.csv")
        if os.path.isfile(path):
            with open(path, newline="") as f:
                reader = csv.DictReader(f)
                header = header or reader.fieldnames
                rows += list(reader)
    if header:
        with open(csv_path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=header)
            w.writeheader()
            w.writerows(rows)
    return 0 if all(r["status"] == "ok" for r in records) else 1


def main(argv=None):
    ap = parser("bench-error-vs-time", __doc__)
    ap.add_argument("--quick", action="store_true", help="Hertz and Cattaneo on coarse meshes (the CTest check)")
    ap.add_argument("--build", default=os.path.join(REPO, "build"), help="build directory (default: build/)")
    ap.add_argument("--out", default="out/error_vs_time")
    ap.add_argument("--scenes", default="", help="comma-separated subset of the plan's scenes")
    ap.add_argument("--refine-max", type=int, default=0, help="no mesh finer than this (reference included)")
    ap.add_argument("--max-run-seconds", type=float, default=None,
                    help="wall-clock budget per run, stopped between steps (program default 120)")
    ap.add_argument("--max-reference-seconds", type=float, default=None,
                    help="budget of each scene's reference run (program default 600)")
    ap.add_argument("--plot-only", action="store_true", help="do not run; redraw from OUT/error_vs_time.csv")
    ap.add_argument("--jobs", type=int, default=1,
                    help="scenes side by side on a Dask LocalCluster (default 1: one at a time, timings undisturbed)")
    ap.add_argument("--scheduler", help="a running Dask scheduler for the scenes (their timings then are the workers')")
    ap.add_argument("--resume", action="store_true", help="keep the scenes already complete in --out")
    ap.add_argument("--check", action="store_true")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    csv_path = os.path.join(args.out, "error_vs_time.csv")
    elapsed = 0.0
    if not args.plot_only:
        bench = os.path.abspath(os.path.join(args.build, "benchmarks", "bench_error_time"))
        ensure_binary(args.build, bench)
        t0 = time.monotonic()
        rc = run_scenes(args, bench, csv_path)
        elapsed = time.monotonic() - t0
        if rc != 0:
            print("warning: a scene's bench_error_time did not finish; plotting the rows written", file=sys.stderr)
            if not os.path.isfile(csv_path):
                return 1
    rows = read_rows(csv_path)
    if rows and "status" not in rows[0]:
        sys.exit(f"error: {csv_path} is from an older bench_error_time (no status column); rebuild and rerun")
    for path in plot(rows, args.out):
        print("wrote", path)
    print("wrote", csv_path)
    with open(os.path.join(args.out, "tables.md"), "w") as f:
        f.write(markdown_tables(rows))
    print("wrote", os.path.join(args.out, "tables.md"))
    default_study = not (args.quick or args.scenes or args.refine_max or args.plot_only
                         or args.max_run_seconds is not None or args.max_reference_seconds is not None)
    if rows:
        summary(rows, default_study, elapsed if not args.plot_only else sum(fnum(r["cost_s"]) for r in rows))
    if args.check:
        problems = check(rows)
        for p in problems:
            print("check failed:", p, file=sys.stderr)
        if problems:
            return 1
        print("check passed:", len(rows), "runs")
    return 0
