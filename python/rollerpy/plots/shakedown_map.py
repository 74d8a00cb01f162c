"""Draws a shakedown map from a study's study.csv (`rollerpy study` with
problems/studies/shakedown_map.toml; docs/validation.md, "Shakedown map"): every point at its
traction coefficient mu (contact.friction) and load p0/k (passes.p0_over_k), marked by its verdict
(elastic shakedown, plastic shakedown, ratchetting; failed points as crosses), with Johnson's
shakedown limit over it (rollerpy.line_contact_shakedown) and the surface limit 1/mu; prints a
Markdown table of the points against that limit.

With --melan SCENE, also the limit `roller shakedown-limit` computes for the scene's own strip
(Melan's bound from its elastic press, q = mu p; docs/model.md) at mu = 0, 0.05, ..., 0.4: the
line the finite strip and mesh give beside the half-plane's.

usage: ./rollerpy plot-shakedown-map STUDY_CSV [--out MAP.png] [--melan SCENE] [--roller build/roller]
Default --out: shakedown_map.png beside the CSV.
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

from ..command import parser
from ..outputs import read_rows
from ..paths import DEFAULT_ROLLER
from ..runner import output_file_problem, save_figure
from ..line_contact_shakedown import shakedown_limit
from . import plt

STYLE = {"elastic_shakedown": ("o", "C2", "elastic shakedown"),
         "plastic_shakedown": ("s", "C1", "plastic shakedown (closed cycle)"),
         "ratchetting": ("^", "C3", "ratchetting"),
         "undetermined": ("D", "0.5", "undetermined")}


def melan_line(roller, scene, mus):
    """p0/k of Melan's bound of `scene` at each traction coefficient (roller shakedown-limit)."""
    limits = []
    with tempfile.TemporaryDirectory() as tmp:
        for mu in mus:
            out = os.path.join(tmp, "limit.json")
            subprocess.run([roller, "shakedown-limit", scene, "--traction", repr(float(mu)), "--json", out],
                           check=True, stdout=subprocess.DEVNULL)
            with open(out) as f:
                limits.append(json.load(f)["elastic"]["p0_over_k"])
    return limits


def main(argv=None):
    ap = parser("plot-shakedown-map", __doc__)
    ap.add_argument("csv")
    ap.add_argument("--out")
    ap.add_argument("--melan", metavar="SCENE", help="draw roller shakedown-limit's line for this scene")
    ap.add_argument("--roller", default=DEFAULT_ROLLER)
    args = ap.parse_args(argv)
    if args.out is not None and output_file_problem(args.out, "--out"):
        print("plot-shakedown-map: " + output_file_problem(args.out, "--out"), file=sys.stderr)
        return 2
    rows = read_rows(args.csv)
    if not rows:
        sys.exit("plot_shakedown_map: %s has no points" % args.csv)
    fig, ax = plt.subplots(figsize=(9.5, 5.5))
    mus = np.linspace(0.0, 0.5, 51)
    ax.plot(mus, [shakedown_limit(m) for m in mus], "k-", label="Johnson: shakedown limit (Melan)")
    ax.plot(mus[mus > 0.15], 1.0 / mus[mus > 0.15], "k:", label="surface limit 1/μ")
    melan = {}
    if args.melan:
        melan_mus = np.linspace(0.0, 0.4, 9)
        melan = dict(zip(melan_mus, melan_line(args.roller, args.melan, melan_mus)))
        ax.plot(list(melan), list(melan.values()), "C0.--", ms=7,
                label="roller shakedown-limit: Melan on %s" % os.path.basename(args.melan))
    seen = set()
    for r in rows:
        mu = float(r["contact.friction"])
        verdict = r.get("passes.verdict") or ""
        if r["status"] != "ok" or verdict not in STYLE:
            ax.plot(mu, float(r["passes.p0_over_k"] or "nan"), "kx", ms=9,
                    label=None if "failed" in seen else "no verdict: the run stopped (study.csv says why)")
            seen.add("failed")
            continue
        marker, colour, label = STYLE[verdict]
        ax.plot(mu, float(r["passes.p0_over_k"]), marker, color=colour, ms=10,
                label=None if verdict in seen else label)
        seen.add(verdict)
    ax.set_xlabel("traction coefficient μ = Q/P (sliding)")
    ax.set_ylabel("load p0/k")
    ax.set_xlim(-0.02, 0.42)
    ax.set_ylim(2.0, 5.0)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    ax.set_title("Shakedown map of a line contact (%d points)" % len(rows))
    fig.tight_layout()
    # The table: each point against Johnson's limit at its mu.
    limits = {}
    if melan:
        print("Melan's bound of %s (roller shakedown-limit): %s" % (
            args.melan, ", ".join("%.3f at μ = %.2f" % (v, m) for m, v in melan.items())))
    print("| p0/k | μ | Johnson's limit | expected | verdict | status | run [s] |")
    print("|---:|---:|---:|---|---|---|---:|")
    for r in rows:
        mu = float(r["contact.friction"])
        limits.setdefault(mu, shakedown_limit(mu))
        load = float(r["passes.p0_over_k"] or "nan")
        expected = "elastic shakedown" if load < limits[mu] else "not elastic shakedown"
        print("| %.2f | %.2f | %.2f | %s | %s | %s | %.0f |" % (
            load, mu, limits[mu], expected, r.get("passes.verdict") or "—", r["status"], float(r["wall_s"])))
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.csv)), "shakedown_map.png")
    save_figure(fig, out, dpi=110)
    print("wrote", out)
