"""Scaling of one increment with the number of dofs, both backends (docs/benchmarks.md).

usage: ./rollerpy bench-scaling [--build build] [--out DIR] [--min-dofs 0] [--max-dofs 1.4e6]
                               [--backends ipopt,penalty] [--cases hertz,z1] [--timeout 3600]
                               [--set KEY=VALUE ...]

Cases: Hertz (frictionless, elastic): the whole indentation in ONE increment, cold start; Z1
(plastic, friction, finite strain): the first rolling increment (step 4, warm from step 3).
For each mesh size: wall time of that increment (solver.csv wall_s) and of the whole process
(cold: scene, mesh, earlier steps, output), solver iterations, peak memory of the roller process
(summary.json), and the time (and MUMPS memory) of one MUMPS analysis + factorisation of the
strip tangent K (bench_factorize) as the unit. The runs are a study per case on the study runner
(`rollerpy study`, DIR/study_CASE/: one point per size and backend, serial so that timings are
not disturbed, resumed when rerun: a study stopped part-way keeps every size it measured; a size
beyond --timeout is recorded as timeout). Writes DIR/scaling.csv, DIR/scaling.png and prints a
Markdown table with the fitted exponent of time against dofs (sizes >= 1e4).
--set adds scene overrides to every run and to the unit factorisation, e.g.
--set linear_solver.out_of_core=true (docs/benchmarks.md, memory).
"""
import csv
import json
import math
import os

from ..command import parser
from ..outputs import read_rows
from ..paths import ROOT
from ..plots import plt
from ..runner import run
from ..study import cli as study_cli
QUIET = ["output.monitor=false", "output.vtu=false", "output.checkpoint_every=0"]
# (label, scene, overrides, measured step); dofs: Hertz 2(60k+1)(30k+1), Z1 2(45k+1)(3k+1).
CASES = {
    "hertz": [("hertz", "problems/hertz.toml",
               [f"mesh.nx={nx}", f"mesh.ny={ny}", f"mesh.refine={k}", "steps.count=1",
                "roller.path=[{steps=[1,1], dy=-0.1}]"], 1)
              for nx, ny, k in [(30, 15, 1), (60, 30, 1), (60, 30, 2), (60, 30, 4), (60, 30, 9), (60, 30, 13),
                                (60, 30, 19)]],
    "z1": [("z1", "problems/z1_outf05.toml", [f"mesh.refine={k}", "steps.count=4"], 4)
           for k in [2, 4, 10, 20, 40, 61]],
}


def dofs_of(label, overrides):
    v = dict(o.split("=", 1) for o in overrides)
    k = int(v.get("mesh.refine", 1))
    if label == "hertz":
        return 2 * (int(v["mesh.nx"]) * k + 1) * (int(v["mesh.ny"]) * k + 1)
    return 2 * (45 * k + 1) * (3 * k + 1)


def run_sizes(args, case, sizes):
    """Runs the sizes of a case as a study (`rollerpy study`, docs/studies.md): one point per size
    and backend, serially (timings undisturbed), resumable (a rerun keeps the sizes measured
    before). Returns {(size index, backend): row}."""
    scene, step = sizes[0][1], sizes[0][3]
    backends = args.backends.split(",")
    out = os.path.join(args.out, "study_" + case)
    os.makedirs(out, exist_ok=True)
    solver = ("step", "wall_s", "iterations", "factorizations", "linearisations", "condensed_dofs", "ipopt_time_s")
    lines = ['title = "scaling: %s"' % case, 'scene = "%s"' % os.path.join(ROOT, scene),
             "backends = [%s]" % ", ".join('"%s"' % b for b in backends), "timeout = %r" % float(args.timeout),
             "collect = [%s]" % ", ".join('"%s"' % c for c in ["ndof", "peak_memory_mb"] +
                                          ["solver.csv:" + k for k in solver]),
             "[set]"] + ['"%s" = %s' % tuple(o.split("=", 1)) for o in QUIET + args.set]
    for _, _, overrides, _ in sizes:
        lines += ["[[point]]"] + ['"%s" = %s' % tuple(o.split("=", 1)) for o in overrides]
    study = os.path.join(out, "study.toml")
    with open(study, "w") as f:
        f.write("\n".join(lines) + "\n")
    if study_cli.main([study, "--out", out, "--serial", "--resume",
                       "--roller", os.path.abspath(os.path.join(args.build, "roller"))]) != 0:
        raise SystemExit("bench-scaling: the study %s did not run" % study)
    study_rows = read_rows(os.path.join(out, "study.csv"))
    results = {}
    for r in study_rows:
        row = {"status": "converged" if r["status"] == "ok" else r["status"],
               # the whole process, cold: reading the scene, meshing, every step before the measured one
               "process_wall_s": float(r["wall_s"]),
               "peak_memory_mb": float(r["peak_memory_mb"] or "nan")}
        if r["solver.csv:step"] and int(r["solver.csv:step"]) == step:
            row["wall_s"] = float(r["solver.csv:wall_s"])
            row["iterations"] = int(r["solver.csv:iterations"])
            for key in solver[3:]:
                row[key] = float(r["solver.csv:" + key] or "nan")
        if r["ndof"]:
            row["dofs"] = int(r["ndof"])
        results[(int(r["index"]) // len(backends), r["backend"])] = row
    return results


def factorization_time(build, scene, overrides, log):
    """(seconds, MB): one MUMPS analysis + factorisation of K (median of 3) and the memory MUMPS took."""
    result = run([os.path.join(build, "benchmarks", "bench_factorize"), scene, "3"] + overrides, log).check()
    fields = result.last_line().split()  # its one line of results comes last
    return float(fields[3]), float(fields[4]) if len(fields) > 4 else float("nan")


def fit_exponent(points):
    pts = [(math.log(n), math.log(t)) for n, t in points if n >= 1e4 and t > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def main(argv=None):
    ap = parser("bench-scaling", __doc__)
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="out/scaling")
    ap.add_argument("--min-dofs", type=float, default=0)
    ap.add_argument("--max-dofs", type=float, default=1.4e6)
    ap.add_argument("--backends", default="ipopt,penalty")
    ap.add_argument("--cases", default="hertz,z1")
    ap.add_argument("--timeout", type=float, default=3600)
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="scene override for every run")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    columns = ["case", "backend", "dofs", "status", "wall_s", "process_wall_s", "iterations", "factorizations",
               "linearisations", "condensed_dofs", "ipopt_time_s", "peak_memory_mb", "factorization_s",
               "factorization_memory_mb", "time_in_factorizations"]
    rows = []
    with open(os.path.join(args.out, "scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for case in args.cases.split(","):
            sizes = [c for c in CASES[case] if args.min_dofs <= dofs_of(c[0], c[2] + args.set) <= args.max_dofs]
            if not sizes:
                continue
            results = run_sizes(args, case, sizes)
            for i, (label, scene, overrides, step) in enumerate(sizes):
                overrides = overrides + args.set
                unit, unit_memory = factorization_time(args.build, scene, overrides,
                                                       os.path.join(args.out, "factorize_%s_%d.log" % (case, i)))
                for backend in args.backends.split(","):
                    r = dict(results.get((i, backend), {"status": "not run"}))
                    r.update({"case": label, "backend": backend, "factorization_s": unit,
                              "factorization_memory_mb": unit_memory, "dofs": r.get("dofs", dofs_of(label, overrides))})
                    if "wall_s" in r:
                        r["time_in_factorizations"] = r["wall_s"] / unit
                    rows.append(r)
                    w.writerow(r)
                    f.flush()
                    print(json.dumps(r), flush=True)
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    print("| case | backend | dofs | status | increment [s] | whole run [s] | iterations | factorisations | "
          "peak memory [MB] | factorisation [s] | its MUMPS memory [MB] | increment / factorisation |")
    print("|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r['case']} | {r['backend']} | {r['dofs']} | {r['status']} | {r.get('wall_s', float('nan')):.3f} | "
              f"{r.get('process_wall_s', float('nan')):.1f} | {r.get('iterations', '')} | "
              f"{r.get('factorizations', float('nan')):.0f} | {r.get('peak_memory_mb', float('nan')):.0f} | "
              f"{r['factorization_s']:.3f} | {r['factorization_memory_mb']:.0f} | "
              f"{r.get('time_in_factorizations', float('nan')):.1f} |")
    for case in dict.fromkeys(r["case"] for r in rows):
        for backend in args.backends.split(","):
            pts = [(r["dofs"], r["wall_s"]) for r in rows if r["case"] == case and r["backend"] == backend
                   and "wall_s" in r and r["status"] == "converged"]
            if pts:
                ax.loglog(*zip(*pts), "o-", label=f"{case} {backend} (N^{fit_exponent(pts):.2f})")
        units = sorted({(r["dofs"], r["factorization_s"]) for r in rows if r["case"] == case})  # one per size
        ax.loglog(*zip(*units), "k--" if case == "hertz" else "k:", alpha=0.5,
                  label=f"{case}: one factorisation of K (N^{fit_exponent(units):.2f})")
    ax.set_xlabel("dofs")
    ax.set_ylabel("wall time of the increment [s]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "scaling.png"), dpi=120)
    for case in dict.fromkeys(r["case"] for r in rows):
        for backend in args.backends.split(","):
            pts = [(r["dofs"], r["wall_s"]) for r in rows if r["case"] == case and r["backend"] == backend
                   and "wall_s" in r and r["status"] == "converged"]
            print(f"{case} {backend}: time ~ N^{fit_exponent(pts):.2f} (sizes >= 1e4)")
    return 0
