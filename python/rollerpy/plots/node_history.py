"""Per-step displacement increments of one node over the steps of one or more runs (PNG + CSV).

usage: ./rollerpy plot-node-history OUT [OUT ...] --node 101
                                     [--labels "V = 6.25 m/s,V = 50 m/s"] [--out DIR]

The node is given in the thesis's 1-based numbering, as in scene files (docs/thesis-meshes.md:
node N is point N-1 of the VTU files; Z4's corner node 101 = set top_right). For every step n
with a step_NNNN.vtu, D(n) = u(n) - u(n-1), the thesis's increments D_x, D_y (Fig. 5.21).
Writes into DIR (default: the first OUT's figures/):
  node<N>_<run>.png     D_x and D_y against the step, one figure per run
  node<N>_overlay.png   D_y (top) and D_x (bottom) of all runs in one figure
  node<N>_history.csv   run, step, time, x0, y0, u_x, u_y, D_x, D_y for every run
Needs numpy and matplotlib from Debian.
"""
import csv
import os
import sys

import numpy as np

from ..command import parser
from ..vtu import available_steps, read_vtu, reference_mesh, step_times, vtu_path
from . import plt


def history(out, index):
    """Steps, times, the node's reference position and displacement per step (u[n] = [u_x, u_y])."""
    steps = available_steps(out)
    if steps[:1] != [0] or steps != list(range(len(steps))):
        sys.exit("plot_node_history: %s needs step_NNNN.vtu for every step from 0" % out)
    points0, _ = reference_mesh(out)
    if index >= len(points0):
        sys.exit("plot_node_history: %s has only %d nodes" % (out, len(points0)))
    times = step_times(out)
    u = [read_vtu(vtu_path(out, step)).point_data["displacement"][index, :2] for step in steps]
    return np.array(steps), np.array([times.get(s, np.nan) for s in steps]), points0[index], np.array(u)


def main(argv=None):
    ap = parser("plot-node-history", __doc__)
    ap.add_argument("outs", nargs="+", metavar="OUT")
    ap.add_argument("--node", type=int, required=True, help="node number, 1-based thesis numbering")
    ap.add_argument("--labels", default="", help="comma-separated legend names (default: folder names)")
    ap.add_argument("--out", help="folder for the PNGs and the CSV (default: the first OUT's figures/)")
    args = ap.parse_args(argv)
    names = [os.path.basename(os.path.normpath(o)) for o in args.outs]
    labels = [t.strip() for t in args.labels.split(",")] if args.labels else names
    if len(labels) != len(args.outs):
        sys.exit("plot_node_history: %d labels for %d runs" % (len(labels), len(args.outs)))
    dest = args.out or os.path.join(args.outs[0], "figures")
    os.makedirs(dest, exist_ok=True)
    tag = "node%d" % args.node

    runs = []
    for out, name, label in zip(args.outs, names, labels):
        steps, times, x0, u = history(out, args.node - 1)
        runs.append((name, label, steps, times, x0, u, np.vstack([[np.nan, np.nan], np.diff(u, axis=0)])))
    where = "node %d at (%g, %g)" % (args.node, *runs[0][4])

    with open(os.path.join(dest, tag + "_history.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["run", "step", "time", "x0", "y0", "u_x", "u_y", "D_x", "D_y"])
        for name, _, steps, times, x0, u, d in runs:
            for i, step in enumerate(steps):
                w.writerow([name, step, "%.6g" % times[i], "%g" % x0[0], "%g" % x0[1],
                            "%.6e" % u[i, 0], "%.6e" % u[i, 1],
                            "" if i == 0 else "%.6e" % d[i, 0], "" if i == 0 else "%.6e" % d[i, 1]])

    for name, label, steps, _, _, _, d in runs:
        fig, ax = plt.subplots(figsize=(7, 4))
        ax.plot(steps[1:], d[1:, 0], "o-", ms=3, label="D_x")
        ax.plot(steps[1:], d[1:, 1], "s--", ms=3, label="D_y")
        ax.axhline(0.0, color="0.5", lw=0.5)
        ax.set_xlabel("step n")
        ax.set_ylabel("D(n) = u(n) − u(n−1) [mm]")
        ax.set_title("%s: displacement increments of %s" % (label, where), fontsize=10)
        ax.xaxis.get_major_locator().set_params(integer=True)
        ax.legend()
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(os.path.join(dest, "%s_%s.png" % (tag, name)), dpi=120)
        plt.close(fig)

    fig, axes = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    for component, ax in zip((1, 0), axes):
        for _, label, steps, _, _, _, d in runs:
            ax.plot(steps[1:], d[1:, component], "o-", ms=3, label=label)
        ax.axhline(0.0, color="0.5", lw=0.5)
        ax.set_ylabel("D_%s(n) [mm]" % "xy"[component])
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    axes[0].set_title("displacement increments of %s" % where, fontsize=10)
    axes[1].set_xlabel("step n")
    axes[1].xaxis.get_major_locator().set_params(integer=True)
    fig.tight_layout()
    fig.savefig(os.path.join(dest, tag + "_overlay.png"), dpi=120)
    plt.close(fig)
    print("plot_node_history: figures and %s_history.csv in %s" % (tag, dest))
