"""Thesis-style figures (PNG) from a roller output folder.

usage: ./rollerpy plot-scene OUT_DIR [--steps 4,7] [--profile-steps 0-12]
                              [--pressure-steps 13] [--hertz] [--mesh-steps 3,6]
                              [--fields sqrt_I2,tau_xy] [--pairs 23/47,63/71]
                              [--compare OTHER_OUT --compare-steps 47]
                              [--spacing sqrt_I2=10] [--label NAME]
                              [--levels 50 | --levels=-50,-30,10,50] [--values element]
                              [--xlim 80,160] [--ylim 30,50] [--whole]
                              [--mesh-pairs 3/6] [--mark-nodes 5,101]

Reads fields.pvd / step_NNNN.vtu, contact.csv, roller.csv and scene.resolved.toml of a run and
writes into OUT_DIR/figures/:
  map_<field>_step<N>.png   contour maps of sqrt(I2) (thesis: the von Mises value, so the plastic
                            zone is bounded by the yield stress), tau_xx, tau_yy, tau_xy, the total
                            strains eps_xx, eps_yy, eps_xy, the strains of the step's increment
                            deps_xx, deps_yy, deps_xy (the thesis's updated-Lagrangian strain), u_y.
                            The window is the contact region of that step (six contact half-widths
                            around it, down to that depth; --whole: the whole strip; --xlim/--ylim:
                            your own). --values element draws the element (integration-point
                            mean) values unsmoothed, which keeps peaks that nodal averaging blunts;
                            --levels sets the contour lines: a spacing (50) or a list of values
  profile.png               top-surface profile over the steps, u_y magnified x100
  pressure.png              contact pressure p_n (and p_t) along x at the chosen steps, around the
                            nodes in contact
  mesh_step<N>.png          deformed mesh (true scale and u magnified), with the roller's circle
                            and the nodes of --mark-nodes labelled
  mesh_steps<A>-<B>.png     (--mesh-pairs A/B) the deformed meshes of steps A (solid) and B
                            (dashed) in one figure
  compare_pressure.png      (--compare) p_n of both runs at the comparison steps
  hertz.png                 (--hertz) the last step's pressure against the Hertz solution
  overlay_<field>_steps<A>-<B>.png
                            (--pairs A/B) the contour lines of steps A (solid) and B (dashed) in one
                            map with the same levels, the thesis's way; up to four steps per group
                            (solid, dashed, dash-dot, dotted)
  compare_<field>_step<N>.png
                            (--compare) the contour lines of OTHER_OUT (the reference, solid) and
                            of this run (dashed) at step N, same levels (e.g. pass 1 vs pass 2)
Needs numpy and matplotlib from Debian (python3-numpy, python3-matplotlib).
"""
import math
import os
import sys

import matplotlib.tri as mtri
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator

from ..command import parser
from ..outputs import read_contact, read_rows, read_scene, roller_at, touching_x
from ..vtu import available_steps, read_vtu, reference_mesh, top_nodes, triangles, vtu_path
from . import plt


def von_mises(s):  # s: [xx, yy, zz, xy]
    p = (s[:, 0] + s[:, 1] + s[:, 2]) / 3.0
    d = s[:, :3] - p[:, None]
    return np.sqrt(1.5 * (np.sum(d * d, axis=1) + 2.0 * s[:, 3] ** 2))


def parse_steps(text, last):
    steps = []
    for part in text.split(","):
        if "-" in part:
            a, b = part.split("-")
            steps.extend(range(int(a), int(b) + 1))
        elif part:
            steps.append(int(part))
    return [s for s in steps if 0 <= s <= last]


FIELDS = {  # name: (label, nodal value from the VTU point data, element value from the cell data)
    "sqrt_I2": ("√I2 (von Mises) [MPa]", lambda pd: von_mises(pd["stress_nodal"]), lambda cd: cd["von_mises"]),
    "tau_xx": ("τ_xx [MPa]", lambda pd: pd["stress_nodal"][:, 0], lambda cd: cd["stress"][:, 0]),
    "tau_yy": ("τ_yy [MPa]", lambda pd: pd["stress_nodal"][:, 1], lambda cd: cd["stress"][:, 1]),
    "tau_xy": ("τ_xy [MPa]", lambda pd: pd["stress_nodal"][:, 3], lambda cd: cd["stress"][:, 3]),
    "eps_xx": ("ε_xx [-]", lambda pd: pd["strain_nodal"][:, 0], lambda cd: cd["strain"][:, 0]),
    "eps_yy": ("ε_yy [-]", lambda pd: pd["strain_nodal"][:, 1], lambda cd: cd["strain"][:, 1]),
    "eps_xy": ("ε_xy [-]", lambda pd: pd["strain_nodal"][:, 3], lambda cd: cd["strain"][:, 3]),
    "deps_xx": ("Δε_xx of the step [-]", lambda pd: pd["strain_increment_nodal"][:, 0],
                lambda cd: cd["strain_increment"][:, 0]),
    "deps_yy": ("Δε_yy of the step [-]", lambda pd: pd["strain_increment_nodal"][:, 1],
                lambda cd: cd["strain_increment"][:, 1]),
    "deps_xy": ("Δε_xy of the step [-]", lambda pd: pd["strain_increment_nodal"][:, 3],
                lambda cd: cd["strain_increment"][:, 3]),
    "u_y": ("u_y [mm]", lambda pd: pd["displacement"][:, 1], None),
}
STRESSES = ["sqrt_I2", "tau_xx", "tau_yy", "tau_xy"]


def strip_figure(points, extra, window=None):
    """A figure whose height follows the aspect ratio of the strip (or of the window
    ((x0, x1), (y0, y1))), plus `extra` inches for labels."""
    span = points.max(axis=0) - points.min(axis=0)
    if window:
        span = np.array([window[0][1] - window[0][0], window[1][1] - window[1][0]])
    return plt.subplots(figsize=(11, extra + min(9.0 * span[1] / span[0], 9.0)), layout="constrained")


def contact_window(out, step, points):
    """The map window of a step: the nodes in contact (contact.csv) and six contact half-widths
    around them, down to that depth (at least 2 mm, at most the strip); without contact at that
    step the roller's centre (roller.csv) plus and minus the strip's height; None without a roller."""
    top, bottom = points[:, 1].max(), points[:, 1].min()
    left, right = points[:, 0].min(), points[:, 0].max()
    xs = touching_x(read_contact(out), step) if os.path.exists(os.path.join(out, "contact.csv")) else []
    if xs:
        centre, half = 0.5 * (min(xs) + max(xs)), max(0.5 * (max(xs) - min(xs)), 1.0)
        reach = 6.0 * half
    elif os.path.exists(os.path.join(out, "roller.csv")):
        roller = [r for r in read_rows(os.path.join(out, "roller.csv")) if int(r["step"]) == step]
        if not roller:
            return None
        centre, reach = float(roller[-1]["xc"]), top - bottom
    else:
        return None
    x0, x1 = max(left, centre - reach), min(right, centre + reach)
    y0 = max(bottom, top - max(reach, 2.0))
    return (x0, x1), (y0, top + 0.02 * (top - y0))


def contour_levels(values, levels):
    """Explicit levels: a list of values, or a spacing (one number) turned into the multiples of
    it inside the data's range; None: about ten round values."""
    lo, hi = float(np.min(values)), float(np.max(values))
    if levels is None:
        return [v for v in MaxNLocator(nbins=10).tick_values(lo, hi) if lo < v < hi]
    if len(levels) == 1:
        step = levels[0]
        return [k * step for k in range(math.floor(lo / step), math.ceil(hi / step) + 1) if lo < k * step < hi]
    return [v for v in levels if lo < v < hi]


def label_lines(ax, cs):
    """Contour labels that stay readable: every other level when there are many, inline, small."""
    shown = cs.levels if len(cs.levels) <= 8 else cs.levels[::2]
    ax.clabel(cs, shown, inline=True, fmt="%g", fontsize=7, inline_spacing=3)


def contour_maps(out, figs, steps, fields, levels=None, element_values=False, xlim=None, ylim=None, whole=False):
    for step in steps:
        vtu = read_vtu(vtu_path(out, step))
        points, elements, pd, cd = vtu.points, vtu.elements, vtu.point_data, vtu.cell_data
        tris = triangles(elements)
        tri = mtri.Triangulation(points[:, 0], points[:, 1], tris)
        # The element each triangle came from (Q4: two triangles per element).
        owner = np.repeat(np.arange(len(elements)), [1 if len(e) == 3 else 2 for e in elements])
        window = None if whole else contact_window(out, step, points)
        if xlim or ylim:
            window = (xlim or (points[:, 0].min(), points[:, 0].max()),
                      ylim or (points[:, 1].min(), points[:, 1].max()))
        for name in fields:
            label, nodal, element = FIELDS[name]
            use_elements = element_values and element is not None
            values = element(cd)[owner] if use_elements else nodal(pd)
            fig, ax = strip_figure(points, 2.0, window)
            if use_elements:
                cs = ax.tripcolor(tri, facecolors=values, cmap="viridis", shading="flat")
            else:
                cs = ax.tricontourf(tri, values, levels=20, cmap="viridis")
                lines = contour_levels(values, levels)
                if lines:
                    label_lines(ax, ax.tricontour(tri, values, levels=lines, colors="k", linewidths=0.4))
            ax.set_aspect("equal")
            if window:
                ax.set_xlim(*window[0])
                ax.set_ylim(*window[1])
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("y [mm]")
            ax.set_title("%s, step %d%s" % (label, step, ", element values" if use_elements else ""))
            fig.colorbar(cs, ax=ax, label=label, location="bottom", aspect=60, shrink=0.7)
            fig.savefig(os.path.join(figs, "map_%s_step%d.png" % (name, step)), dpi=110, bbox_inches="tight")
            plt.close(fig)


def boundary_edges(points, elements):
    """The mesh outline: element edges that belong to one element only, as [[p, q], ...]."""
    count = {}
    for e in elements:
        for a, b in zip(e, np.roll(e, -1)):
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
    return [points[list(k)] for k, n in count.items() if n == 1]


LINES = [("solid", "k"), ("dashed", "C3"), ("dashdot", "C0"), ("dotted", "C2")]


def overlay(path, name, curves, title, spacing=None, levels=None):
    """Contour lines of one field from several (out, step, legend) in one map, the thesis's way:
    the same levels (every `spacing`, or about ten round values), the first solid, then dashed,
    dash-dot, dotted; lines labelled with values. Each curve is drawn on its own deformed mesh;
    the outline is the first curve's."""
    label, get, _ = FIELDS[name]
    data = []
    for out, step, _ in curves:
        vtu = read_vtu(vtu_path(out, step))
        tri = mtri.Triangulation(vtu.points[:, 0], vtu.points[:, 1], triangles(vtu.elements))
        data.append((tri, get(vtu.point_data), vtu.points, vtu.elements))
    values = np.concatenate([d[1] for d in data])
    levels = contour_levels(values, [spacing] if spacing else levels)
    points, elements = data[0][2], data[0][3]
    fig, ax = strip_figure(points, 1.2)
    ax.add_collection(LineCollection(boundary_edges(points, elements), colors="0.5", linewidths=0.8))
    handles = []
    for (tri, v, _, _), (_, _, legend), (style, color) in zip(data, curves, LINES):
        cs = ax.tricontour(tri, v, levels=levels, colors=color, linestyles=style, linewidths=0.9)
        label_lines(ax, cs)
        handles.append(Line2D([], [], color=color, linestyle=style, label=legend))
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title("%s: %s" % (label, title), fontsize=10)
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8,
              title="levels: %s %s" % (", ".join("%g" % v for v in levels) if len(levels) <= 6 else
                                       "every %g" % (levels[1] - levels[0]), label.split("[")[-1].rstrip("]"))
              if len(levels) > 1 else None,
              title_fontsize=7)
    fig.savefig(path, dpi=130, bbox_inches="tight")
    plt.close(fig)


def step_overlays(out, figs, groups, fields, run, spacing, levels=None):
    for group in groups:
        for name in fields:
            overlay(os.path.join(figs, "overlay_%s_steps%s.png" % (name, "-".join(map(str, group)))), name,
                    [(out, step, "step %d" % step) for step in group],
                    "%s, steps %s" % (run, ", ".join(map(str, group))), spacing.get(name), levels)


def run_comparison(out, other, figs, steps, fields, label, other_label, spacing, levels=None):
    for step in steps:
        for name in fields:
            overlay(os.path.join(figs, "compare_%s_step%d.png" % (name, step)), name,
                    [(other, step, other_label), (out, step, label)],
                    "%s vs %s, step %d" % (other_label, label, step), spacing.get(name), levels)


def profile(out, figs, steps):
    points0, _ = reference_mesh(out)
    top = top_nodes(points0)
    order = top[np.argsort(points0[top, 0])]
    fig, ax = plt.subplots(figsize=(10, 4))
    colours = curve_colours(len(steps))
    for step, colour in zip(steps, colours):
        u = read_vtu(vtu_path(out, step)).point_data["displacement"]
        ax.plot(points0[order, 0] + u[order, 0], 100.0 * u[order, 1], label="step %d" % step, lw=1, color=colour)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("u_y × 100 [mm]")
    ax.set_title("top surface profile (u_y magnified ×100)")
    ax.legend(fontsize=7, ncol=max(1, len(steps) // 12 + 1))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "profile.png"), dpi=110)
    plt.close(fig)


def curve_colours(n):
    """n distinguishable colours: the tab10 cycle up to ten curves, a continuous map beyond (no
    colour repeats)."""
    if n <= 10:
        return ["C%d" % i for i in range(n)]
    return [plt.get_cmap("turbo")(v) for v in np.linspace(0.05, 0.95, n)]


def pressure(out, figs, steps):
    rows = read_contact(out)
    fig, ax = plt.subplots(figsize=(8, 4))
    touching = []
    for step, colour in zip(steps, curve_colours(len(steps))):
        r = sorted((row for row in rows if int(row["step"]) == step), key=lambda row: float(row["x"]))
        if not r:
            continue
        x = [float(row["x"]) for row in r]
        touching += [float(row["x"]) for row in r if row["status"] != "open"]
        ax.plot(x, [float(row["p_n"]) for row in r], "o-", ms=3, color=colour, label="step %d" % step)
        ax.plot(x, [float(row["p_t"]) for row in r], "s--", ms=2, color=colour)
    if touching:  # around the nodes in contact: a few nodes of a long strip
        lo, hi = min(touching), max(touching)
        margin = max(hi - lo, 1.0)
        ax.set_xlim(lo - margin, hi + margin)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("contact pressure [MPa]")
    ax.set_title("p_n (solid) and p_t (dashed)", fontsize=10)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), ncol=max(1, (len(steps) + 15) // 16))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "pressure.png"), dpi=110)
    plt.close(fig)


def draw_extras(ax, out, step, points, marks):
    """The roller's circle at that step and the marked nodes (thesis numbers), on mesh figures."""
    roller = roller_at(out, step)
    if roller:
        ax.add_patch(plt.Circle((roller.xc, roller.yc), roller.radius, fill=False, color="C0", lw=1.0))
    for node in marks:
        if 1 <= node <= len(points):
            x, y = points[node - 1]
            ax.plot(x, y, "o", color="C3", ms=5)
            ax.annotate(str(node), (x, y), xytext=(4, 4), textcoords="offset points", fontsize=8, color="C3")


def mesh_lines(ax, x, elements, **style):
    ax.add_collection(LineCollection([x[list(e) + [e[0]]] for e in elements], **style))


def deformed_mesh(out, figs, steps, marks=()):
    points0, elements = reference_mesh(out)
    for step in steps:
        u = read_vtu(vtu_path(out, step)).point_data["displacement"][:, :2]
        fig, axes = plt.subplots(1, 2, figsize=(12, 4))
        for ax, scale in zip(axes, (1.0, 10.0)):
            x = points0 + scale * u
            mesh_lines(ax, points0, elements, colors="0.8", linewidths=0.5)
            mesh_lines(ax, x, elements, colors="k", linewidths=0.7)
            draw_extras(ax, out, step, x, marks)
            ax.set_aspect("equal")
            span = points0.max(axis=0) - points0.min(axis=0)
            ax.set_xlim(points0[:, 0].min() - 0.05 * span[0], points0[:, 0].max() + 0.05 * span[0])
            ax.set_ylim(points0[:, 1].min() - 0.05 * span[1], points0[:, 1].max() + 0.3 * span[1])
            ax.set_title("step %d, displacement ×%g (grey: initial)" % (step, scale))
        fig.tight_layout()
        fig.savefig(os.path.join(figs, "mesh_step%d.png" % step), dpi=110)
        plt.close(fig)


def mesh_overlay(out, figs, group, marks=()):
    """The deformed meshes of two to four steps in one figure (the thesis's 5.8 ii: steps 3 and 6),
    at true scale and with displacements ×10, the first solid, then dashed, dash-dot, dotted."""
    points0, elements = reference_mesh(out)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4))
    for ax, scale in zip(axes, (1.0, 10.0)):
        handles = []
        for step, (style, colour) in zip(group, LINES):
            x = points0 + scale * read_vtu(vtu_path(out, step)).point_data["displacement"][:, :2]
            mesh_lines(ax, x, elements, colors=colour, linestyles=style, linewidths=0.7)
            handles.append(Line2D([], [], color=colour, linestyle=style, label="step %d" % step))
        draw_extras(ax, out, group[-1], points0, marks)
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_title("displacement ×%g" % scale)
        ax.legend(handles=handles, fontsize=8, loc="lower right")
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "mesh_steps%s.png" % "-".join(map(str, group))), dpi=110)
    plt.close(fig)


def pressure_comparison(out, other, figs, steps, label, other_label):
    """p_n of two runs at the same steps in one plot (the thesis's 5.7: OUTF05 and OUTF10)."""
    fig, ax = plt.subplots(figsize=(8, 4))
    colours = curve_colours(len(steps))
    touching = []
    for run, name, style in ((other, other_label, "o-"), (out, label, "s--")):
        rows = read_contact(run)
        for step, colour in zip(steps, colours):
            r = sorted((row for row in rows if int(row["step"]) == step), key=lambda row: float(row["x"]))
            if not r:
                continue
            touching += [float(row["x"]) for row in r if row["status"] != "open"]
            ax.plot([float(row["x"]) for row in r], [float(row["p_n"]) for row in r], style, ms=3, color=colour,
                    label="%s, step %d" % (name, step))
    if touching:
        lo, hi = min(touching), max(touching)
        margin = max(hi - lo, 1.0)
        ax.set_xlim(lo - margin, hi + margin)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("p_n [MPa]")
    ax.set_title("contact pressure: %s (solid) and %s (dashed)" % (other_label, label), fontsize=10)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "compare_pressure.png"), dpi=110)
    plt.close(fig)


def hertz(out, figs):
    scene = read_scene(out)
    rows = read_contact(out)
    last = max(int(r["step"]) for r in rows)
    roller = read_rows(os.path.join(out, "roller.csv"))[-1]
    load, xc = float(roller["fy"]), float(roller["xc"])
    e, nu, radius = scene["material"]["E"], scene["material"]["nu"], scene["roller"]["radius"]
    e_star = e / (1 - nu * nu)
    a = math.sqrt(4 * load * radius / (math.pi * e_star))
    p0 = 2 * load / (math.pi * a)
    r = sorted((row for row in rows if int(row["step"]) == last), key=lambda row: float(row["x"]))
    x = np.array([float(row["x"]) - xc for row in r])
    p = np.array([float(row["p_n"]) if row["status"] != "open" else 0.0 for row in r])
    xs = np.linspace(-1.5 * a, 1.5 * a, 400)
    ps = p0 * np.sqrt(np.clip(1 - (xs / a) ** 2, 0, None))
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(xs, ps, "k-", label="Hertz: a = %.3f mm, p0 = %.0f MPa" % (a, p0))
    ax.plot(x, p, "o", ms=4, label="roller (%s)" % scene.get("contact", {}).get("backend", "?"))
    ax.set_xlim(-1.5 * a, 1.5 * a)
    ax.set_xlabel("x − x_c [mm]")
    ax.set_ylabel("p [MPa]")
    ax.set_title("Hertz line contact, P = %.0f N/mm" % load)
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "hertz.png"), dpi=110)
    plt.close(fig)


def number_list(option, text, count=None):
    """A comma-separated list of numbers (None when empty); exits naming the option otherwise."""
    if not text:
        return None
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        sys.exit("plot_scene: %s %s: expected numbers separated by commas" % (option, text))
    if count is not None and len(values) != count:
        sys.exit("plot_scene: %s %s: expected %d numbers" % (option, text, count))
    return values


def main(argv=None):
    ap = parser("plot-scene", __doc__)
    ap.add_argument("out")
    ap.add_argument("--steps", default="", help="steps for the contour maps, e.g. 4,7 (default: the last)")
    ap.add_argument("--profile-steps", default="", help="steps for the surface profile, e.g. 0-12 (default: all)")
    ap.add_argument("--pressure-steps", default="", help="steps for the pressure plot (default: the last)")
    ap.add_argument("--mesh-steps", default="", help="steps for deformed-mesh plots, e.g. 3,6")
    ap.add_argument("--hertz", action="store_true", help="also plot the pressure against Hertz")
    ap.add_argument("--fields", default="",
                    help="fields for maps, overlays and comparisons, from %s (default: all for "
                         "the maps, the four stresses for overlays and comparisons)" % ",".join(FIELDS))
    ap.add_argument("--pairs", default="",
                    help="step groups overlaid in one map, e.g. 23/47,63/71 or 6/8/14/16 "
                         "(solid, dashed, dash-dot, dotted)")
    ap.add_argument("--compare", metavar="OTHER_OUT",
                    help="a reference run whose contour lines (solid) are overlaid with this run's (dashed)")
    ap.add_argument("--compare-steps", default="", help="steps of the comparison (default: the last)")
    ap.add_argument("--spacing", default="",
                    help="contour spacing of overlays and comparisons per field, e.g. sqrt_I2=10,tau_xy=10 "
                         "(default: about ten round levels)")
    ap.add_argument("--label", help="this run's name in titles and legends (default: the folder name)")
    ap.add_argument("--compare-label", help="OTHER_OUT's name in the legend (default: its folder name)")
    ap.add_argument("--levels", default="",
                    help="contour lines of maps, overlays and comparisons: a spacing (50) or a list of values "
                         "(--levels=-50,-30,10,50: with = when the list starts with a minus); default: about ten "
                         "round values (--spacing FIELD=... wins for its field)")
    ap.add_argument("--values", choices=["nodal", "element"], default="nodal",
                    help="maps of nodal averages (smooth contours) or of element values (unsmoothed peaks)")
    ap.add_argument("--xlim", default="", help="map window in x, e.g. 80,160 [mm] (default: the contact region)")
    ap.add_argument("--ylim", default="", help="map window in y, e.g. 30,50 [mm] (default: the contact region)")
    ap.add_argument("--whole", action="store_true", help="maps of the whole strip instead of the contact region")
    ap.add_argument("--mesh-pairs", default="",
                    help="deformed meshes of a group of steps in one figure, e.g. 3/6 (mesh_steps3-6.png)")
    ap.add_argument("--mark-nodes", default="",
                    help="nodes (thesis numbers) marked and labelled on the mesh figures, e.g. 5,101")
    args = ap.parse_args(argv)
    steps = available_steps(args.out)
    if not steps:
        sys.exit("plot_scene: no step_NNNN.vtu in %s (was the run made with output.vtu = true?)" % args.out)
    last = steps[-1]
    figs = os.path.join(args.out, "figures")
    os.makedirs(figs, exist_ok=True)
    fields = [f for f in args.fields.split(",") if f]
    if any(f not in FIELDS for f in fields):
        sys.exit("plot_scene: --fields: known fields are %s" % ", ".join(FIELDS))
    groups = [[int(n) for n in g.split("/")] for g in args.pairs.split(",") if g]
    if any(not 2 <= len(g) <= len(LINES) or set(g) - set(steps) for g in groups):
        sys.exit("plot_scene: --pairs: groups of 2 to %d steps that have VTU files" % len(LINES))
    spacing = {k: float(v) for k, v in (item.split("=") for item in args.spacing.split(",") if item)}
    if set(spacing) - set(FIELDS) or any(v <= 0 for v in spacing.values()):
        sys.exit("plot_scene: --spacing: FIELD=positive value, fields %s" % ", ".join(FIELDS))
    label = args.label or os.path.basename(os.path.normpath(args.out))
    levels, xlim, ylim = number_list("--levels", args.levels), number_list("--xlim", args.xlim, 2), \
        number_list("--ylim", args.ylim, 2)
    if levels is not None and len(levels) == 1 and levels[0] <= 0:
        sys.exit("plot_scene: --levels %s: a spacing must be positive" % args.levels)
    for name, lim in (("--xlim", xlim), ("--ylim", ylim)):
        if lim is not None and not lim[0] < lim[1]:
            sys.exit("plot_scene: %s %g,%g: expected LOW,HIGH with LOW < HIGH" % (name, lim[0], lim[1]))
    contour_maps(args.out, figs, parse_steps(args.steps, last) or [last], fields or list(FIELDS), levels,
                 args.values == "element", xlim, ylim, args.whole)
    step_overlays(args.out, figs, groups, fields or STRESSES, label, spacing, levels)
    if args.compare:
        other = available_steps(args.compare)
        both = [n for n in parse_steps(args.compare_steps, last) or [last] if n in other]
        other_label = args.compare_label or os.path.basename(os.path.normpath(args.compare))
        run_comparison(args.out, args.compare, figs, both, fields or STRESSES, label, other_label, spacing, levels)
        if os.path.exists(os.path.join(args.out, "contact.csv")) and \
                os.path.exists(os.path.join(args.compare, "contact.csv")):
            pressure_comparison(args.out, args.compare, figs, both, label, other_label)
    profile(args.out, figs, parse_steps(args.profile_steps, last) or steps)
    if os.path.exists(os.path.join(args.out, "contact.csv")):
        pressure(args.out, figs, parse_steps(args.pressure_steps, last) or [last])
    marks = [int(v) for v in number_list("--mark-nodes", args.mark_nodes) or []]
    if args.mesh_steps:
        deformed_mesh(args.out, figs, parse_steps(args.mesh_steps, last), marks)
    mesh_groups = [[int(n) for n in g.split("/")] for g in args.mesh_pairs.split(",") if g]
    if any(not 2 <= len(g) <= len(LINES) or set(g) - set(steps) for g in mesh_groups):
        sys.exit("plot_scene: --mesh-pairs: groups of 2 to %d steps that have VTU files" % len(LINES))
    for group in mesh_groups:
        mesh_overlay(args.out, figs, group, marks)
    if args.hertz:
        hertz(args.out, figs)
    print("plot_scene: figures in %s" % figs)
