"""The roller's force and position against the step (docs/figures.md): roller.csv's fx, fy
[N/mm] with the prescribed forces (fx_prescribed, fy_prescribed) dashed where the scene gives
them, and the centre's xc, yc [mm]; the passes of a multi-pass run marked.

usage: ./rollerpy plot-forces OUT_DIR [--label NAME] [--output FILE]

Writes OUT_DIR/figures/forces.png (or FILE). `rollerpy plot-scene` draws the same figure.
"""
import os
import sys

import numpy as np

from ..command import parser
from ..outputs import num, read_rows
from ..runner import output_file_problem, save_figure
from . import plt


def forces_figure(out, label=None):
    """fx, fy, xc and yc of roller.csv against the step in three panels; returns the figure."""
    rows = read_rows(os.path.join(out, "roller.csv"))
    step = np.array([int(r["step"]) for r in rows])
    column = {k: np.array([num(r.get(k)) for r in rows]) for k in
              ("fx", "fy", "xc", "yc", "fx_prescribed", "fy_prescribed")}
    fig, axes = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True, layout="constrained",
                             gridspec_kw={"height_ratios": [2, 1, 1]})
    for name, colour in (("fx", "C0"), ("fy", "C3")):
        axes[0].plot(step, column[name], "o-", ms=2.5, lw=1.0, color=colour, label=name)
        given = column[name + "_prescribed"]
        if np.isfinite(given).any():  # empty cells (steps with prescribed motion) are nan: gaps
            axes[0].plot(step, given, "--", lw=1.4, color=colour, label=name + "_prescribed")
    axes[0].axhline(0.0, color="0.6", lw=0.6)
    axes[0].set_ylabel("force [N/mm]")
    axes[0].legend(fontsize=8, loc="best")
    for ax, name in ((axes[1], "xc"), (axes[2], "yc")):
        ax.plot(step, column[name], "o-", ms=2.5, lw=1.0, color="k")
        ax.set_ylabel("%s [mm]" % name)
        ax.ticklabel_format(axis="y", useOffset=False)  # positions as read, not as "+1.999e2" offsets
    mark_passes(axes, rows, step)
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("step")
    axes[0].set_title("force of the strip on the roller, and the roller's centre: %s"
                      % (label or os.path.basename(os.path.normpath(out))), fontsize=10)
    return fig


def mark_passes(axes, rows, step):
    """A dotted line where a pass begins (roller.csv's pass column), named on the top panel."""
    passes = [int(r.get("pass") or 1) for r in rows]
    starts = [i for i in range(1, len(passes)) if passes[i] != passes[i - 1]]
    for i in starts:
        for ax in axes:
            ax.axvline(step[i] - 0.5, color="0.4", lw=0.8, ls=":")
        axes[0].annotate("pass %d" % passes[i], (step[i] - 0.5, 1.0), xycoords=("data", "axes fraction"),
                         xytext=(3, -10), textcoords="offset points", fontsize=8, color="0.3")


def main(argv=None):
    ap = parser("plot-forces", __doc__)
    ap.add_argument("out")
    ap.add_argument("--label", help="the run's name in the title (default: the folder name)")
    ap.add_argument("--output", help="the PNG to write (default: OUT_DIR/figures/forces.png)")
    args = ap.parse_args(argv)
    if not os.path.exists(os.path.join(args.out, "roller.csv")):
        sys.exit("plot-forces: %s has no roller.csv (a run without a roller, or not an output folder)" % args.out)
    if args.output is not None and output_file_problem(args.output, "--output"):
        print("plot-forces: " + output_file_problem(args.output, "--output"), file=sys.stderr)
        return 2
    path = args.output or os.path.join(args.out, "figures", "forces.png")
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig = forces_figure(args.out, args.label)
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    print("plot-forces: %s" % path)
