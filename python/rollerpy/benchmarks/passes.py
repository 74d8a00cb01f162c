"""Repeated passes under load: the time of one pass and of a multi-pass study, both backends and
the stationary method (docs/benchmarks.md, "Repeated passes under load" and "With the steady
Jacobian").

usage: ./rollerpy bench-passes [--roller build/roller] [--out out/bench_passes]
                              [--element-size 0.1] [--load 4.5]
                              [--passes ipopt=5,penalty=1] [--timeout 7200]

The strip is the shakedown scene of docs/validation.md (`rollerpy make-shakedown-scenes`) with
uniform elements of --element-size under the track (0.1 mm: 40 across 2a, 4.8e4 dofs), at p0/k =
--load. --passes names the runs: a contact backend (ipopt, penalty) marches its passes,
`stationary` solves them with passes.method = "stationary" on the roller's contact (its default),
`stationary_hertz` under the Hertz load (ipopt=5,stationary=5 is the plan's comparison). Each runs
the number of passes given, once, alone: one run of several minutes is its own average over ~20
increments a pass, so the table gives per-pass times from solver.csv (wall_s summed over the pass's
steps) beside the whole process's wall time, peak memory (/usr/bin/time -v) and output folder size.
Writes OUT/passes.csv and prints a Markdown table; each run's log (roller's output and
/usr/bin/time's report) is OUT/<run>.log.
"""
import csv
import os
import re

from ..command import parser
from ..outputs import num, read_rows
from ..paths import DEFAULT_ROLLER
from ..runner import contact_option, roller_command, run as run_roller
from ..validation.make_shakedown_scenes import write_scenes


def folder_bytes(path):
    return sum(os.path.getsize(os.path.join(d, f)) for d, _, files in os.walk(path) for f in files)


def run_options(name):
    """A run of --passes: `stationary` is the stationary method (`stationary_hertz` under the Hertz load), any
    other name a contact backend."""
    if name == "stationary":
        return ["--set", 'passes.method="stationary"']
    if name == "stationary_hertz":
        return ["--set", 'passes.method="stationary"', "--set", 'passes.stationary_contact="hertz"']
    return contact_option(name)


def run(args, scene, backend, passes):
    out = os.path.join(args.out, "%s_%dpasses" % (backend, passes))
    cmd = ["/usr/bin/time", "-v"] + roller_command(args.roller, scene, out, "--overwrite", *run_options(backend),
                                                   "--set", "passes.count=%d" % passes)
    print("$", " ".join(cmd), flush=True)
    result = run_roller(cmd, out + ".log", args.timeout)
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", result.output())
    rows = read_rows(os.path.join(out, "solver.csv")) if result.exit_code == 0 else []
    per_pass = {}
    for r in rows:
        per_pass[int(r["pass"])] = per_pass.get(int(r["pass"]), 0.0) + num(r["wall_s"])
    dofs = None
    with open(os.path.join(out, "summary.json")) as f:
        m = re.search(r'"ndof"\s*:\s*(\d+)', f.read())
        dofs = int(m.group(1)) if m else None
    return {"backend": backend, "passes": passes, "rc": result.status.value if result.timed_out else result.exit_code,
            "dofs": dofs, "wall_s": round(result.wall_s, 1),
            "per_pass_s": " ".join("%.0f" % per_pass[k] for k in sorted(per_pass)),
            "peak_mib": round(int(rss.group(1)) / 1024.0) if rss else None,
            "folder_mb": round(folder_bytes(out) / 1e6, 1)}


def main(argv=None):
    ap = parser("bench-passes", __doc__)
    ap.add_argument("--roller", default=DEFAULT_ROLLER)
    ap.add_argument("--out", default="out/bench_passes")
    ap.add_argument("--element-size", default="0.1")
    ap.add_argument("--load", default="4.5")
    ap.add_argument("--passes", default="ipopt=5,penalty=1")
    ap.add_argument("--timeout", type=float, default=7200)
    args = ap.parse_args(argv)
    scene, = write_scenes([float(args.load)], 5, float(args.element_size), args.out)
    print("wrote", scene)
    rows = []
    for item in args.passes.split(","):
        backend, passes = item.split("=")
        rows.append(run(args, scene, backend, int(passes)))
        print(rows[-1], flush=True)
    with open(os.path.join(args.out, "passes.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print("\n| backend | dofs | passes | wall time | per pass (solver.csv wall_s) | peak memory | output folder |")
    print("|---|---:|---:|---:|---|---:|---:|")
    for r in rows:
        status = "" if r["rc"] == 0 else " (exit %s)" % r["rc"]
        print("| %s | %s | %d | %.0f s%s | %s s | %s MiB | %s MB |" % (
            r["backend"], r["dofs"], r["passes"], r["wall_s"], status, r["per_pass_s"], r["peak_mib"],
            r["folder_mb"]))
