"""Stiff and extreme cases (docs/stability.md): every case on both contact backends.

usage: ./rollerpy stability [--out out/stability] [--only CASE,CASE]
                           [--timeout 600] [--roller ./build/roller]
                           [--no-run] [--source TEXT]

Runs `roller run` once per case and backend (one process at a time, each under a timeout,
killed with its process group when it exceeds it) into OUT/<case>/<backend>/ (log beside it:
OUT/<case>/<backend>.log), then measures every run:
  exit code, converged steps / total, wall time, cuts, the largest |r|/F of an accepted step,
  max penetration (solver.csv max_penetration, summary.json, and -gap from contact.csv),
  friction-cone violation max(|p_t| - mu p_n)+ over all contact.csv rows (absolute [MPa] and
  relative to the largest p_n of the run),
  non-finite numbers in ANY output file: csv cells, json values (nlohmann writes NaN as null,
  so null counts too), every DataArray of every VTU (rollerpy.scan, rollerpy.vtu),
  every float of the CBOR state files, and nan/inf tokens in the text files (pvd, toml, log),
  the failure message (summary.json "message", else the last "error:" line of the log).
Writes OUT/stability.csv and OUT/table.md (the Markdown table of docs/stability.md).
--no-run re-measures the existing outputs without running roller.
The cases, their base scenes and what "dt x10" means: docs/stability.md.
"""
import csv
import math
import os
import re
import shutil
import subprocess
import time

import numpy as np

from ..command import parser
from ..outputs import num, read_rows, read_scene, read_summary
from ..paths import ROOT
from ..runner import contact_option, roller_command, run
from ..scan import scan_outputs

Z1 = "problems/z1_outf05.toml"
HERTZ = "problems/hertz.toml"
Z4 = "problems/z4_v25.toml"
THIN = "problems/stability_thin.toml"

Z1_ROLL = "{steps=[4,13], dx=-40.0, slip=0.03, harmonic={amplitude=0.1, wavelength=20.0}}"
Z1_TOP_ROW = "6.666666666666667"  # Z1's top row of elements (20 mm over 3 rows), the layer

# (id, what, base scene, extra arguments, remark)
CASES = [
    ("z1_base", "Z1 OUTF05 as is (reference)", Z1, [], ""),
    ("et0", "E_T = 0 (perfect plasticity)", Z1, ["--set", "material.kappa=0.0"], ""),
    ("et09", "E_T = 0.9 E", Z1, ["--set", "material.kappa=0.9"], ""),
    ("mu0", "mu = 0", Z1, ["--set", "contact.friction=0.0"], ""),
    ("mu1", "mu = 1", Z1, ["--set", "contact.friction=1.0"], ""),
    ("indent10", "indentation 10 % of H (2 mm)", Z1,
     ["--set", "roller.path=[{steps=[1,3], dy=-2.0}, %s]" % Z1_ROLL], ""),
    ("penalty1e12", "penalty factor 1e12 (kN = 1e12 E* l/h)", Z1,
     ["--set", "contact.penalty.factor=1e12"], "ipopt: setting unused"),
    ("penalty1e8", "(extra) penalty factor 1e8, below the round-off limit", Z1,
     ["--set", "contact.penalty.factor=1e8"], "ipopt: setting unused"),
    ("ipopt_tol12", "Ipopt tol 1e-12", Z1, ["--set", "contact.ipopt.tol=1e-12"],
     "penalty: setting unused"),
    ("nu0499_z1", "(extra) nu = 0.499 on Z1 (T3, plastic, rolling)", Z1, ["--set", "material.nu=0.499"], ""),
    ("hertz_base", "Hertz as is (nu = 0.3, reference)", HERTZ, [], ""),
    ("nu049", "nu = 0.49", HERTZ, ["--set", "material.nu=0.49"], ""),
    ("nu0499", "nu = 0.499", HERTZ, ["--set", "material.nu=0.499"], ""),
    ("nu0499_bbar", "nu = 0.499, B-bar Q4", HERTZ,
     ["--set", "material.nu=0.499", "--set", "mesh.q4_formulation=bbar"], ""),
    ("thin", "strip H = 1 mm under R = 300 mm", THIN, [], ""),
    ("thin_half", "(extra) strip H = 0.5 mm (1 mm full thickness) under R = 300 mm", THIN,
     ["--set", "mesh.height=0.5", "--set", "roller.centre=[30.0, 300.5]",
      "--set", "roller.path=[{steps=[1,3], dy=-0.015}, {steps=[4,10], dx=-14.0, slip=0.03}]"], ""),
    ("z4_base", "Z4 25 m/s as is (reference)", Z4, [], ""),
    ("impact200", "impact at 200 m/s (dt = 1e-5 s)", Z4, ["--set", "steps.dt=1e-5"], ""),
    ("dt_small", "dt / 10 at the same speed (200 steps)", Z4,
     ["--set", "steps.dt=8e-6", "--steps", "200",
      "--set", "roller.path=[{steps=[1,200], dx=-40.0, slip=0.0}]"], ""),
    ("dt_large", "dt x 10 at the same speed (2 steps)", Z4,
     ["--set", "steps.dt=8e-4", "--steps", "2",
      "--set", "roller.path=[{steps=[1,2], dx=-40.0, slip=0.0}]"], ""),
    ("dt_small_fast", "(extra) dt / 10, same path per step (250 m/s)", Z4,
     ["--set", "steps.dt=8e-6"], ""),
    ("dt_large_slow", "(extra) dt x 10, same path per step (2.5 m/s)", Z4,
     ["--set", "steps.dt=8e-4"], ""),
    ("layers", "stiffness ratio 1e6 between two strip layers: steel over a core of E = 0.21 MPa", Z1,
     ["--set", "material.E=0.21", "--set", "layer=[{thickness=%s, E=2.1e5, kappa=0.07}]" % Z1_TOP_ROW], ""),
    ("layers_soft", "(extra) stiffness ratio 1e6: a layer of E = 0.21 MPa over steel", Z1,
     ["--set", "layer=[{thickness=%s, E=0.21, kappa=0.07}]" % Z1_TOP_ROW], ""),
]
BACKENDS = ["penalty", "ipopt"]


# ---------------------------------------------------------------- running


def run_one(roller, scene, extra, backend, out, log, timeout):
    """A fresh run of the scene into `out` (an earlier one removed), its log in `log`: a RunResult."""
    if os.path.isdir(out):
        shutil.rmtree(out)
    return run(roller_command(roller, scene, out, *contact_option(backend), *extra), log, timeout)


def shell_command(cmd):
    def q(a):
        return "'%s'" % a if re.search(r"[\s\[\]{}=,]", a) and not a.startswith("--") else a
    return " ".join(q(a) for a in cmd)


# ---------------------------------------------------------------- measuring

def measure(case, scene, backend, out, log, rc, timed_out, wall):
    summary = read_summary(out, missing_ok=True)
    resolved = read_scene(out) if os.path.exists(os.path.join(out, "scene.resolved.toml")) else {}
    solver = read_rows(os.path.join(out, "solver.csv"), missing_ok=True)
    contact = read_rows(os.path.join(out, "contact.csv"), missing_ok=True)
    mu = resolved.get("contact", {}).get("friction", float("nan"))
    tol = resolved.get("newton", {}).get("residual_tolerance", float("nan"))

    total = summary.get("steps", resolved.get("steps", {}).get("count", ""))
    done = summary.get("steps_done", sum(r.get("status") == "converged" for r in solver))
    accepted = [r for r in solver if r.get("status") == "converged"]
    pen_solver = max([num(r["max_penetration"]) for r in solver], default=float("nan"))
    pen_summary = num(summary.get("max_penetration"))
    pen_gap = max([-num(r["gap"]) for r in contact] + [0.0]) if contact else float("nan")
    pn = np.array([num(r["p_n"]) for r in contact]) if contact else np.zeros(0)
    pt = np.array([num(r["p_t"]) for r in contact]) if contact else np.zeros(0)
    cone = float(np.max(np.maximum(np.abs(pt) - mu * pn, 0.0))) if len(pn) else float("nan")
    pn_max = float(np.max(pn)) if len(pn) else float("nan")
    scan = scan_outputs(out, log)
    n_files, nonfinite = scan.files, scan.problems(out)

    message = summary.get("message", "")
    if timed_out:
        message = "TIMEOUT: killed after %.0f s" % wall
    elif rc != 0 and not summary:
        with open(log, errors="replace") as f:
            errors = [ln.strip() for ln in f if ln.startswith("error")]
        message = errors[-1] if errors else "(no message)"
    note = ""
    if scene == HERTZ:
        note = hertz_note(out, resolved)
    return {
        "case": case, "backend": backend, "exit_code": "timeout" if timed_out else rc,
        "steps_converged": done, "steps_total": total, "wall_s": round(wall, 2),
        "cuts": summary.get("cuts_total", sum(int(num(r.get("cuts"))) for r in solver if r.get("cuts"))),
        "max_accepted_residual": max([num(r["residual"]) for r in accepted], default=float("nan")),
        "residual_tolerance": tol,
        "pen_solver_csv": pen_solver, "pen_summary": pen_summary, "pen_contact_gap": pen_gap,
        "max_penetration": np.nanmax([pen_solver, pen_summary, pen_gap, -1.0]),
        "mu": mu, "max_p_n": pn_max, "cone_violation": cone,
        "cone_violation_rel": cone / pn_max if pn_max > 0 else float("nan"),
        "files_scanned": n_files, "nonfinite": "; ".join(nonfinite), "note": note,
        "message": message,
    }


def hertz_note(out, resolved):
    """Largest p_n of the last step against the Hertz p0 for the measured load."""
    roller = read_rows(os.path.join(out, "roller.csv"), missing_ok=True)
    contact = read_rows(os.path.join(out, "contact.csv"), missing_ok=True)
    if not roller or not contact:
        return ""
    last = roller[-1]["step"]
    load = abs(num(roller[-1]["fy"]))
    mat = resolved["material"]
    e_star = mat["E"] / (1.0 - mat.get("nu", 0.3) ** 2)
    p0 = math.sqrt(load * e_star / (math.pi * resolved["roller"]["radius"]))
    pmax = max(num(r["p_n"]) for r in contact if r["step"] == last)
    return "P = %.0f N/mm, max p_n / p0(Hertz) = %.3f" % (load, pmax / p0)


# ---------------------------------------------------------------- report

FIELDS = ["case", "backend", "exit_code", "steps_converged", "steps_total", "wall_s", "cuts",
          "max_accepted_residual", "residual_tolerance", "max_penetration", "pen_solver_csv",
          "pen_summary", "pen_contact_gap", "mu", "max_p_n", "cone_violation", "cone_violation_rel",
          "files_scanned", "nonfinite", "note", "message", "command"]


def g(x, fmt="%.2g"):
    if isinstance(x, float):
        return "—" if math.isnan(x) else fmt % x
    return str(x)


def markdown(rows, whats):
    lines = ["| case | base | backend | exit | steps | wall [s] | cuts | max accepted \\|r\\|/F | "
             "max pen. [mm] | cone viol. [MPa] (rel.) | NaN/Inf | message / note |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        what, base = whats[r["case"]]
        cone = "—" if math.isnan(r["cone_violation"]) else "%s (%s)" % (
            g(r["cone_violation"]), g(r["cone_violation_rel"]))
        text = r["message"] if r["exit_code"] != 0 else r["note"]
        lines.append("| %s: %s | %s | %s | %s | %s/%s | %.1f | %s | %s | %s | %s | %s | %s |" % (
            r["case"], what, base, r["backend"], r["exit_code"], r["steps_converged"],
            r["steps_total"], r["wall_s"], r["cuts"], g(r.get("max_accepted_residual", float("nan"))),
            g(r["max_penetration"]), cone,
            r["nonfinite"] or "none",
            text.replace("|", "\\|")))
    return "\n".join(lines) + "\n"


def provenance(roller, source):
    """Which source the measured binary was built from (the working tree is shared)."""
    if not source:
        try:
            source = "working tree " + subprocess.run(
                ["git", "describe", "--always", "--dirty"], capture_output=True, text=True,
                check=True).stdout.strip()
        except (OSError, subprocess.CalledProcessError):
            source = "unknown"
    built = time.strftime("%Y-%m-%d %H:%M", time.gmtime(os.path.getmtime(roller))) if os.path.exists(roller) else "?"
    return "Measured %s UTC with %s (built %s UTC; source: %s)." % (
        time.strftime("%Y-%m-%d %H:%M", time.gmtime()), roller, built, source)


def main(argv=None):
    ap = parser("stability", __doc__)
    ap.add_argument("--out", default="out/stability")
    ap.add_argument("--only", default="", help="comma-separated case ids")
    ap.add_argument("--timeout", type=float, default=600.0)
    ap.add_argument("--roller", default="./build/roller")
    ap.add_argument("--no-run", action="store_true", help="measure existing outputs only")
    ap.add_argument("--source", default="", help="what the binary was built from (for table.md; "
                    "default: git describe of this working tree)")
    args = ap.parse_args(argv)
    os.chdir(ROOT)
    only = set(filter(None, args.only.split(",")))
    os.makedirs(args.out, exist_ok=True)

    rows, whats = [], {}
    t_start = time.monotonic()
    for case, what, scene, extra, remark in CASES:
        if only and case not in only:
            continue
        whats[case] = (what, os.path.splitext(os.path.basename(scene))[0])
        for backend in BACKENDS:
            out = os.path.join(args.out, case, backend)
            log = os.path.join(args.out, case, backend + ".log")
            os.makedirs(os.path.dirname(log), exist_ok=True)
            cmd = [args.roller, "run", scene, "--out", out, "--contact", backend] + extra
            if args.no_run:
                rc, timed_out, wall = None, False, float("nan")
                if os.path.exists(os.path.join(out, "summary.json")):
                    s = read_summary(out)
                    rc, wall = (0 if s.get("converged") else 1), s.get("wall_s", float("nan"))
            else:
                result = run_one(args.roller, scene, extra, backend, out, log, args.timeout)
                cmd, rc, timed_out, wall = result.command, result.exit_code, result.timed_out, result.wall_s
            r = measure(case, scene, backend, out, log, rc, timed_out, wall)
            if remark and backend in remark.split(":")[0]:
                r["note"] = (r["note"] + "; " if r["note"] else "") + remark
            r["command"] = shell_command(cmd)
            rows.append(r)
            print("%-12s %-8s exit %-7s steps %s/%s  %7.1f s  pen %-8s cone %-8s nonfinite: %s  %s" % (
                case, backend, r["exit_code"], r["steps_converged"], r["steps_total"], r["wall_s"],
                g(r["max_penetration"]), g(r["cone_violation"]), r["nonfinite"] or "none",
                r["message"] if r["exit_code"] != 0 else ""), flush=True)

    with open(os.path.join(args.out, "stability.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    with open(os.path.join(args.out, "table.md"), "w") as f:
        f.write(provenance(args.roller, args.source) + "\n\n" + markdown(rows, whats))
    print("%d runs in %.0f s; %s, %s" % (
        len(rows), time.monotonic() - t_start,
        os.path.join(args.out, "stability.csv"), os.path.join(args.out, "table.md")))
