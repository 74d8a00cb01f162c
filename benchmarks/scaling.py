#!/usr/bin/python3
"""Scaling of one increment with the number of dofs, both backends (docs/benchmarks.md).

usage: /usr/bin/python3 benchmarks/scaling.py [--build build] [--out DIR] [--min-dofs 0] [--max-dofs 1.4e6]
                                              [--backends ipopt,penalty] [--cases hertz,z1] [--timeout 3600]
                                              [--set KEY=VALUE ...]

Cases: Hertz (frictionless, elastic): the whole indentation in ONE increment, cold start; Z1
(plastic, friction, finite strain): the first rolling increment (step 4, warm from step 3).
For each mesh size: wall time of that increment (solver.csv wall_s) and of the whole process
(cold: scene, mesh, earlier steps, output), solver iterations, peak memory of the whole process
(/usr/bin/time -v), and the time (and MUMPS memory) of one MUMPS analysis + factorisation of the
strip tangent K (bench_factorize) as the unit. Writes DIR/scaling.csv, DIR/scaling.png and
prints a Markdown table with the fitted exponent of time against dofs (sizes >= 1e4).
--set adds scene overrides to every run and to the unit factorisation, e.g.
--set linear_solver.out_of_core=true (docs/benchmarks.md, memory).
"""
import argparse
import csv
import json
import math
import os
import re
import signal
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

QUIET = ["--set", "output.monitor=false", "--set", "output.vtu=false", "--set", "output.checkpoint_every=0"]
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


def run_case(build, label, scene, overrides, step, backend, out, timeout):
    run_dir = os.path.join(out, "runs", f"{label}_{backend}_{dofs_of(label, overrides)}")
    cmd = ["/usr/bin/time", "-v", os.path.join(build, "roller"), "run", scene, "--out", run_dir,
           "--contact", backend] + QUIET
    for o in overrides:
        cmd += ["--set", o]
    # Own process group: on a timeout roller goes down with /usr/bin/time, not left running.
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        _, stderr = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        return {"status": f"timeout ({timeout:.0f} s)"}
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", stderr)
    # Whole process, cold: reading the scene, meshing, every step before the measured one, output.
    elapsed = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", stderr)
    row = {"status": "converged" if p.returncode == 0 else f"exit {p.returncode}",
           "peak_memory_mb": int(rss.group(1)) / 1024 if rss else float("nan"),
           "process_wall_s": sum(float(x) * 60 ** i for i, x in enumerate(reversed(elapsed.group(1).split(":"))))
           if elapsed else float("nan")}
    with open(os.path.join(run_dir, "solver.csv")) as f:
        steps = {int(r["step"]): r for r in csv.DictReader(f)}
    if step in steps:
        row["wall_s"] = float(steps[step]["wall_s"])
        row["iterations"] = int(steps[step]["iterations"])
        for key in ("factorizations", "linearisations", "condensed_dofs", "ipopt_time_s"):
            row[key] = float(steps[step].get(key, "nan"))
    with open(os.path.join(run_dir, "summary.json")) as f:
        row["dofs"] = json.load(f)["ndof"]
    return row


def factorization_time(build, scene, overrides):
    """(seconds, MB): one MUMPS analysis + factorisation of K (median of 3) and the memory MUMPS took."""
    p = subprocess.run([os.path.join(build, "benchmarks", "bench_factorize"), scene, "3"] + overrides,
                       capture_output=True, text=True, check=True)
    fields = p.stdout.split()
    return float(fields[3]), float(fields[4]) if len(fields) > 4 else float("nan")


def fit_exponent(points):
    pts = [(math.log(n), math.log(t)) for n, t in points if n >= 1e4 and t > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="out/scaling")
    ap.add_argument("--min-dofs", type=float, default=0)
    ap.add_argument("--max-dofs", type=float, default=1.4e6)
    ap.add_argument("--backends", default="ipopt,penalty")
    ap.add_argument("--cases", default="hertz,z1")
    ap.add_argument("--timeout", type=float, default=3600)
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="scene override for every run")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    columns = ["case", "backend", "dofs", "status", "wall_s", "process_wall_s", "iterations", "factorizations",
               "linearisations", "condensed_dofs", "ipopt_time_s", "peak_memory_mb", "factorization_s",
               "factorization_memory_mb", "time_in_factorizations"]
    rows = []
    timed_out = {}
    # Written row by row: a study stopped part-way keeps every size it measured.
    with open(os.path.join(args.out, "scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for case in args.cases.split(","):
            for label, scene, overrides, step in CASES[case]:
                overrides = overrides + args.set
                n = dofs_of(label, overrides)
                if n > args.max_dofs or n < args.min_dofs:
                    continue
                unit, unit_memory = factorization_time(args.build, scene, overrides)
                for backend in args.backends.split(","):
                    if (case, backend) in timed_out:  # a larger size would time out as well
                        r = {"status": f"not run: {timed_out[(case, backend)]} timed out"}
                    else:
                        r = run_case(args.build, label, scene, overrides, step, backend, args.out, args.timeout)
                        if r["status"].startswith("timeout"):
                            timed_out[(case, backend)] = f"{n} dofs"
                    r.update({"case": label, "backend": backend, "factorization_s": unit,
                              "factorization_memory_mb": unit_memory, "dofs": r.get("dofs", n)})
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


if __name__ == "__main__":
    sys.exit(main())
