"""Rolling-friction robustness suite (docs/stability.md, "Rolling with friction").

usage: ./rollerpy rolling-suite [--out out/rolling_suite] [--refine 1,2,3]
                               [--mu 0.05,0.15,0.3,0.6]
                               [--creep 0,1e-3,3e-3,1e-2,sliding]
                               [--materials elastic,plastic]
                               [--backends ipopt,penalty] [--timeout 900]
                               [--roller ./build/roller] [--no-run] [--resume]

Steady rolling after a press-in (problems/rolling_friction.toml: the roller pressed 0.1 mm into
a graded elastic strip over steps 1-4, then rolled 4 mm over steps 5-28) over every combination
of friction coefficient, creep ("sliding" = a roller that does not turn, slip 1), refinement,
strip material (elastic, or elastic-plastic: yield stress 1000 MPa, E_T = 0.01 E, so that the
Hertz pressure ~2.8 GPa yields the strip) and backend, each with the backends' DEFAULT settings.
One roller process at a time, each under a timeout (killed with its process group). Per run:
converged / failed / timeout, steps done, step cuts, friction passes per increment (ipopt: NLP
solves of the increment), Q/(mu P) of the last step, wall time, and any nan/inf in the outputs.
Writes OUT/suite.csv (one row per run, written as it goes: an interrupted suite keeps its rows)
and OUT/table.md; --no-run re-measures existing outputs; --resume keeps the rows of OUT/suite.csv
whose run finished (converged or failed) and runs only the others, so a suite can span sessions.
"""
import csv
import itertools
import os
import statistics

from ..command import parser
from ..outputs import num, read_rows
from ..paths import ROOT
from ..scan import scan_outputs
from .stability import provenance, run_one

SCENE = "problems/rolling_friction.toml"
PLASTIC = ["--set", "material.yield_stress=1000.0", "--set", "material.tangent_modulus=2100.0"]
COLUMNS = ["material", "mu", "creep", "refine", "backend", "status", "steps", "cuts",
           "passes_per_increment", "max_passes", "q_over_mu_p", "wall_s", "nonfinite", "message"]


def path_override(creep):
    """The scene's two path segments with the rolling segment's creep replaced."""
    slip = 1.0 if creep == "sliding" else float(creep)
    return ["--set", "roller.path=[{steps=[1,4], dy=-0.1}, {steps=[5,28], dx=4.0, slip=%r}]" % slip]


def measure(out, log, rc, timed_out, wall, mu):
    solver = read_rows(os.path.join(out, "solver.csv"), missing_ok=True)
    roller = read_rows(os.path.join(out, "roller.csv"), missing_ok=True)
    done = [r for r in solver if r.get("status") == "converged"]
    # Friction passes of an increment: the ipopt backend's NLP solves (one per Tresca pass);
    # the penalty backend has none (its return map uses the current F_N).
    passes = [num(r["nlp_solves"]) for r in done if num(r.get("nlp_solves")) > 0]
    q = float("nan")
    if roller and len(roller) > 1:
        last = roller[-1]
        fy = num(last["fy"])
        if fy > 0 and mu > 0:
            q = abs(num(last["fx"])) / (mu * fy)
    problems = scan_outputs(out, log).flagged
    message = ""
    if rc != 0:
        with open(log, errors="replace") as f:
            errors = [line.strip() for line in f if line.startswith("error:")]
        message = errors[-1][:160] if errors else ("timeout" if timed_out else "exit %s" % rc)
    status = "timeout" if timed_out else ("converged" if rc == 0 else "failed")
    return {
        "status": status, "steps": len(done),
        "cuts": int(sum(num(r["cuts"]) for r in solver)) if solver else 0,
        "passes_per_increment": "%.1f" % statistics.mean(passes) if passes else "",
        "max_passes": "%d" % max(passes) if passes else "",
        "q_over_mu_p": "%.4f" % q if q == q else "",
        "wall_s": "%.1f" % wall if wall is not None else "",
        "nonfinite": len(problems), "message": message,
    }


def markdown(rows):
    lines = ["| strip | μ | creep | refine | backend | result | cuts | passes/incr (max) | Q/μP | time [s] |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        passes = "%s (%s)" % (r["passes_per_increment"], r["max_passes"]) if r["passes_per_increment"] else "—"
        result = r["status"] if r["status"] != "converged" else "ok"
        if r["nonfinite"] not in ("0", 0):
            result += ", nan/inf in output"
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["material"], r["mu"], r["creep"], r["refine"], r["backend"], result, r["cuts"], passes,
            r["q_over_mu_p"] or "—", r["wall_s"]))
    n = len(rows)
    ok = sum(1 for r in rows if r["status"] == "converged" and r["nonfinite"] in ("0", 0))
    lines.append("")
    lines.append("%d of %d runs converged with the backends' default settings." % (ok, n))
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = parser("rolling-suite", __doc__)
    ap.add_argument("--out", default="out/rolling_suite")
    ap.add_argument("--refine", default="1,2,3")
    ap.add_argument("--mu", default="0.05,0.15,0.3,0.6")
    ap.add_argument("--creep", default="0,1e-3,3e-3,1e-2,sliding")
    ap.add_argument("--materials", default="elastic,plastic")
    ap.add_argument("--backends", default="ipopt,penalty")
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--roller", default="./build/roller")
    ap.add_argument("--no-run", action="store_true")
    ap.add_argument("--resume", action="store_true")
    args = ap.parse_args(argv)
    os.chdir(ROOT)
    os.makedirs(args.out, exist_ok=True)
    grid = itertools.product(args.materials.split(","), args.mu.split(","), args.creep.split(","),
                             args.refine.split(","), args.backends.split(","))
    rows = []
    table = os.path.join(args.out, "suite.csv")
    finished = {}
    if args.resume and os.path.exists(table):
        for r in read_rows(table):
            if r.get("status") in ("converged", "failed"):
                finished[(r["material"], r["mu"], r["creep"], r["refine"], r["backend"])] = r
    with open(table, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        # Finished rows first, so that an interrupted resume loses none of them.
        writer.writerows(finished.values())
        f.flush()
        for material, mu, creep, refine, backend in grid:
            key = (material, mu, creep, refine, backend)
            if key in finished:
                rows.append(finished[key])
                continue
            name = "%s_mu%s_creep%s_r%s_%s" % key
            out = os.path.join(args.out, name)
            log = out + ".log"
            extra = ["--refine", refine, "--set", "contact.friction=%s" % mu] + path_override(creep)
            if material == "plastic":
                extra += PLASTIC
            if args.no_run:
                rc = 0 if os.path.exists(os.path.join(out, "summary.json")) and \
                    '"converged": true' in open(os.path.join(out, "summary.json")).read() else 1
                timed_out, wall = False, None
            else:
                result = run_one(args.roller, SCENE, extra, backend, out, log, args.timeout)
                rc, timed_out, wall = result.exit_code, result.timed_out, result.wall_s
            row = {"material": material, "mu": mu, "creep": creep, "refine": refine, "backend": backend}
            row.update(measure(out, log, rc, timed_out, wall, float(mu)))
            rows.append({k: str(v) for k, v in row.items()})
            writer.writerow(row)
            f.flush()
            print("%-40s %-9s steps %3s cuts %3s passes %5s Q/muP %6s %7s s %s" % (
                name, row["status"], row["steps"], row["cuts"], row["passes_per_increment"] or "-",
                row["q_over_mu_p"] or "-", row["wall_s"], row["message"]), flush=True)
    # Again, in the grid's order, after the rows of earlier runs outside this grid (kept).
    grid_keys = set(itertools.product(args.materials.split(","), args.mu.split(","), args.creep.split(","),
                                      args.refine.split(","), args.backends.split(",")))
    rows = [r for k, r in finished.items() if k not in grid_keys] + rows
    with open(table, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    with open(os.path.join(args.out, "table.md"), "w") as f:
        f.write(markdown(rows))
        f.write("\n" + provenance(args.roller, "") + "\n")
    print("wrote %s and %s" % (os.path.join(args.out, "suite.csv"), os.path.join(args.out, "table.md")))
