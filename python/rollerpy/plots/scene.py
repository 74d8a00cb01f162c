"""Report and thesis figures (PNG) from a roller output folder (docs/figures.md).

usage: ./rollerpy plot-scene OUT_DIR [--steps 4,7] [--profile-steps 0-12]
                              [--pressure-steps 13] [--hertz] [--hertz-step N] [--mesh-steps 3,6]
                              [--fields von_mises,stress_xy] [--pairs 23/47,63/71]
                              [--compare OTHER_OUT --compare-steps 47]
                              [--spacing von_mises=10] [--label NAME]
                              [--levels 50 | --levels=-50,-30,10,50] [--values element]
                              [--xlim 80,160] [--ylim 30,50] [--whole]
                              [--mesh-pairs 3/6] [--mark-nodes 5,101]

Reads fields.pvd / step_NNNN.vtu, contact.csv, roller.csv and scene.resolved.toml of a run and
writes into OUT_DIR/figures/. Fields have the VTU's names (docs/scenes.md, Outputs): stress_xx,
stress_yy, stress_zz, stress_xy [MPa]; sqrt_I2 = sqrt(s:s/2) and von_mises = sqrt(3/2 s:s) (the
thesis's "sqrt(I2)": the plastic zone is bounded by the yield stress) [MPa]; eq_plastic_strain;
strain_xx, ... (total), strain_increment_xx, ... (the step's increment, the thesis's
updated-Lagrangian strain); displacement_x, displacement_y [mm].
  map_<field>_step<N>.png   contour maps: signed fields in a diverging map centred at zero,
                            magnitudes in a sequential one; colour bands and lines at the same
                            levels; the roller's circle. The window is the contact region of that
                            step (--whole: the whole strip; --xlim/--ylim: your own); --values
                            element draws the element values unsmoothed; --levels sets the levels:
                            a spacing (50) or a list of values
  forces.png                the roller's force and position against the step (rollerpy plot-forces)
  profile.png               top-surface profile over the steps, displacement_y magnified x100
  pressure.png              p_n (and p_t) along x at the chosen steps, around the nodes in contact
  mesh_step<N>.png          deformed mesh (true scale and u magnified), with the roller's circle
                            and the nodes of --mark-nodes labelled
  mesh_steps<A>-<B>.png     (--mesh-pairs A/B) the deformed meshes of steps A (solid) and B
                            (dashed) in one figure
  compare_pressure.png      (--compare) p_n of both runs at the comparison steps
  hertz.png                 (--hertz, --hertz-step N) p_n at step N (default: the last step whose
                            roller carries load, fy > 0) against the Hertz solution at its load
  overlay_<field>_steps<A>-<B>.png
                            (--pairs A/B) the contour lines of steps A (solid) and B (dashed) in one
                            map with the same levels, the thesis's way; up to four steps per group
  compare_<field>_step<N>.png
                            (--compare) the contour lines of OTHER_OUT (the reference, solid) and
                            of this run (dashed) at step N, same levels (e.g. pass 1 vs pass 2)
A step that the run does not have, or an unknown field, stops with a message (exit 1).
Needs numpy and matplotlib from Debian (python3-numpy, python3-matplotlib).
"""
import math
import os
import sys
from dataclasses import dataclass

import matplotlib.tri as mtri
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.lines import Line2D
from matplotlib.ticker import FuncFormatter

from ..command import parser
from ..outputs import read_contact, read_rows, read_scene, roller_at, touching_x
from ..vtu import available_steps, read_vtu, reference_mesh, top_nodes, triangles, vtu_path
from . import forces, plt
from .fields import (FIELDS, MAP_FIELDS, STRESSES, colours, contour_levels, label_lines, number_text,
                     unknown_field)


class PlotError(Exception):
    """A request the run cannot answer (a step it does not have, an unknown field); main() prints
    the message and exits 1."""


def parse_steps(option, text, available):
    """The steps of an option (4,7 or 0-12), each one the run has; [] for an empty option."""
    steps = []
    try:
        for part in (p for p in text.replace("/", ",").split(",") if p):
            a, _, b = part.partition("-")
            steps.extend(range(int(a), int(b) + 1) if b else [int(a)])
    except ValueError:
        raise PlotError("%s %s: expected steps such as 4,7 or 0-12" % (option, text))
    missing = [s for s in steps if s not in set(available)]
    if missing:
        raise PlotError("%s %s: the run has no step %d (it has steps %s)"
                        % (option, text, missing[0], step_ranges(available)))
    return steps


def step_ranges(steps):
    """0-12,20,30-31: a list of steps written short."""
    parts, start = [], None
    for i, s in enumerate(steps):
        start = s if start is None else start
        if i + 1 == len(steps) or steps[i + 1] != s + 1:
            parts.append("%d" % s if s == start else "%d-%d" % (start, s))
            start = None
    return ",".join(parts) or "none"


def strip_window(points):
    top, bottom = points[:, 1].max(), points[:, 1].min()
    return (points[:, 0].min(), points[:, 0].max()), (bottom, top + 0.02 * (top - bottom))


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
    return (x0, x1), (y0, top + 0.08 * (top - y0))  # room above the surface: the roller shows


# A window wider than this many times its height is drawn with y stretched (stated in the title):
# at true scale a whole strip is a thin band whose colours cannot be read.
MAX_ASPECT = 4.0


def window_axes(window, extra):
    """A figure for a map of that window ((x0, x1), (y0, y1)), and the vertical exaggeration."""
    width, height = window[0][1] - window[0][0], window[1][1] - window[1][0]
    stretch = max(1.0, round(width / height / MAX_ASPECT))
    fig, ax = plt.subplots(figsize=(11, extra + min(9.0 * stretch * height / width, 9.0)), layout="constrained")
    ax.set_aspect(stretch)
    ax.set_xlim(*window[0])
    ax.set_ylim(*window[1])
    return fig, ax, stretch


def strip_figure(points, extra):
    """A figure for the whole strip at true scale plus `extra` inches for labels (overlays)."""
    span = points.max(axis=0) - points.min(axis=0)
    return plt.subplots(figsize=(11, extra + min(9.0 * span[1] / span[0], 9.0)), layout="constrained")


def draw_roller(ax, out, step, filled=True):
    """The roller's circle at the step (roller.csv's xc, yc, the scene's radius), if there is one;
    filled grey on maps, an outline over meshes (whose magnified displacements it would hide)."""
    roller = roller_at(out, step)
    if roller:
        ax.add_patch(plt.Circle((roller.xc, roller.yc), roller.radius, facecolor="0.85" if filled else "none",
                                edgecolor="k" if filled else "C0", lw=1.2, alpha=0.8, zorder=2.5))
    return roller


def draw_field(ax, tri, values, field, levels, owner=None):
    """Colour bands and contour lines at the same levels (element values: flat colours, no
    lines); returns the mappable for the colour bar and the levels."""
    cmap, norm = colours(field, values)
    if owner is not None:  # a continuous bar with its own ticks: no levels
        return ax.tripcolor(tri, facecolors=values[owner], cmap=cmap, norm=norm, shading="flat"), []
    lines = contour_levels(values, levels)
    lo, hi = float(np.min(values)), float(np.max(values))
    if hi - lo <= 1e-12 * max(abs(lo), abs(hi), 1e-300):  # a constant field: one colour
        return ax.tripcolor(tri, np.full(len(values), lo), cmap=cmap, norm=norm, shading="gouraud"), []
    bands = ax.tricontourf(tri, values, levels=[lo] + lines + [hi], cmap=cmap, norm=norm)
    if lines:
        label_lines(ax, ax.tricontour(tri, values, levels=lines, colors="k", linewidths=0.5, linestyles="solid"))
    return bands, lines


@dataclass
class Map:
    """A drawn map: the figure (the caller saves and closes it), its map axes, the colour bands
    (their cmap and norm) and the contour levels."""
    fig: object
    ax: object
    bands: object
    levels: list


def map_figure(out, step, name, levels=None, element_values=False, window=None, whole=False):
    """The contour map of one field at one step (a Map). window: ((x0, x1), (y0, y1)), else the
    contact region (whole: the strip)."""
    field = FIELDS[name]
    vtu = read_vtu(vtu_path(out, step))
    tri = mtri.Triangulation(vtu.points[:, 0], vtu.points[:, 1], triangles(vtu.elements))
    use_elements = element_values and field.element is not None
    # The element each triangle came from (Q4: two triangles per element).
    owner = np.repeat(np.arange(len(vtu.elements)), [1 if len(e) == 3 else 2 for e in vtu.elements])
    values = field.element(vtu) if use_elements else field.nodal(vtu)
    window = window or (None if whole else contact_window(out, step, vtu.points)) or strip_window(vtu.points)
    fig, ax, stretch = window_axes(window, 2.0)
    mappable, lines = draw_field(ax, tri, values, field, levels, owner if use_elements else None)
    draw_roller(ax, out, step)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    notes = [field.meaning] if field.meaning else []
    notes += ["element values"] if use_elements else []
    notes += ["y stretched ×%g" % stretch] if stretch > 1 else []
    ax.set_title("%s, step %d%s" % (name, step, "".join(", " + n for n in notes)))
    bar = fig.colorbar(mappable, ax=ax, location="bottom", aspect=60, shrink=0.7,
                       label="%s (min %s, max %s)" % (field.label(name), number_text(float("%.4g" % values.min())),
                                                      number_text(float("%.4g" % values.max()))))
    if lines:  # the bar's ticks at the contour levels, not at the data's extremes
        bar.set_ticks(lines)
        bar.ax.xaxis.set_major_formatter(FuncFormatter(number_text))
    return Map(fig, ax, mappable, lines)


def contour_maps(out, figs, steps, fields, levels=None, element_values=False, window=None, whole=False):
    for step in steps:
        for name in fields:
            fig = map_figure(out, step, name, levels, element_values, window, whole).fig
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
    field = FIELDS[name]
    label = field.label(name)
    data = []
    for out, step, _ in curves:
        vtu = read_vtu(vtu_path(out, step))
        tri = mtri.Triangulation(vtu.points[:, 0], vtu.points[:, 1], triangles(vtu.elements))
        data.append((tri, field.nodal(vtu), vtu.points, vtu.elements))
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
                                       "every %g" % (levels[1] - levels[0]), field.unit)
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
    ax.set_ylabel("displacement_y × 100 [mm]")
    ax.set_title("top surface profile (displacement_y magnified ×100)")
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
    ax.set_ylabel("p_n, p_t [MPa]")
    ax.set_title("p_n (solid) and p_t (dashed)", fontsize=10)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), ncol=max(1, (len(steps) + 15) // 16))
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "pressure.png"), dpi=110)
    plt.close(fig)


def draw_extras(ax, out, step, points, marks):
    """The roller's circle at that step and the marked nodes (thesis numbers), on mesh figures."""
    draw_roller(ax, out, step, filled=False)
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
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("y [mm]")
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
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
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


def loaded_rows(out):
    """roller.csv's last row of each step whose roller carries load, by step: fy > 0 beyond
    round-off (a lifted roller's fy is 1e-5 N/mm, not 0; 1e-4 of the run's largest fy)."""
    rows = read_rows(os.path.join(out, "roller.csv"), missing_ok=True)
    last = {int(r["step"]): r for r in rows}
    largest = max([float(r["fy"] or 0.0) for r in last.values()] + [0.0])
    return {s: r for s, r in last.items() if float(r["fy"] or 0.0) > 1e-4 * largest > 0.0}


def hertz_figure(out, step=None):
    """The nodal pressures at `step` (default: the last step whose roller carries load) against
    the Hertz solution at that step's load fy; returns the figure."""
    loaded = loaded_rows(out)
    if not loaded:
        raise PlotError("--hertz: no step of %s has a roller that carries load (fy > 0 in roller.csv)" % out)
    step = max(loaded) if step is None else step
    if step not in loaded:
        raise PlotError("--hertz-step %d: the roller carries no load at that step; loaded steps: %s"
                        % (step, step_ranges(sorted(loaded))))
    scene = read_scene(out)
    load, xc = float(loaded[step]["fy"]), float(loaded[step]["xc"])
    e, nu, radius = scene["material"]["E"], scene["material"]["nu"], scene["roller"]["radius"]
    a = math.sqrt(4 * load * radius / (math.pi * e / (1 - nu * nu)))
    p0 = 2 * load / (math.pi * a)
    r = sorted((row for row in read_contact(out) if int(row["step"]) == step), key=lambda row: float(row["x"]))
    x = np.array([float(row["x"]) - xc for row in r])
    p = np.array([float(row["p_n"]) if row["status"] != "open" else 0.0 for row in r])
    xs = np.linspace(-1.5 * a, 1.5 * a, 400)
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(xs, p0 * np.sqrt(np.clip(1 - (xs / a) ** 2, 0, None)), "k-",
            label="Hertz: a = %.3f mm, p0 = %.0f MPa" % (a, p0))
    ax.plot(x, p, "o", ms=4, label="roller p_n (%s)" % scene.get("contact", {}).get("backend", "?"))
    ax.set_xlim(-1.5 * a, 1.5 * a)
    ax.set_xlabel("x − xc [mm]")
    ax.set_ylabel("p_n [MPa]")
    ax.set_title("Hertz line contact at step %d, fy = %.0f N/mm" % (step, load))
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def number_list(option, text, count=None):
    """A comma-separated list of numbers (None when empty); PlotError naming the option otherwise."""
    if not text:
        return None
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        raise PlotError("%s %s: expected numbers separated by commas" % (option, text))
    if count is not None and len(values) != count:
        raise PlotError("%s %s: expected %d numbers" % (option, text, count))
    return values


def step_groups(option, text, steps):
    """Groups such as 23/47,6/8/14/16: 2 to 4 steps of the run each."""
    groups = [parse_steps(option, g, steps) for g in text.split(",") if g]
    if any(not 2 <= len(g) <= len(LINES) for g in groups):
        raise PlotError("%s %s: groups of 2 to %d steps" % (option, text, len(LINES)))
    return groups


def arguments():
    ap = parser("plot-scene", __doc__)
    ap.add_argument("out")
    loaded = "(default: the last written step whose roller carries load, else the last)"
    ap.add_argument("--steps", default="", help="steps for the contour maps, e.g. 4,7 " + loaded)
    ap.add_argument("--profile-steps", default="", help="steps for the surface profile, e.g. 0-12 (default: all)")
    ap.add_argument("--pressure-steps", default="", help="steps for the pressure plot " + loaded)
    ap.add_argument("--mesh-steps", default="", help="steps for deformed-mesh plots, e.g. 3,6")
    ap.add_argument("--hertz", action="store_true", help="also plot p_n against Hertz (hertz.png)")
    ap.add_argument("--hertz-step", type=int,
                    help="the step of hertz.png (implies --hertz; default: the last step whose roller carries load)")
    ap.add_argument("--fields", default="",
                    help="fields for maps, overlays and comparisons, from %s (default: all but the zz "
                         "components for the maps, %s for overlays and comparisons)"
                         % (",".join(FIELDS), ",".join(STRESSES)))
    ap.add_argument("--pairs", default="",
                    help="step groups overlaid in one map, e.g. 23/47,63/71 or 6/8/14/16 "
                         "(solid, dashed, dash-dot, dotted)")
    ap.add_argument("--compare", metavar="OTHER_OUT",
                    help="a reference run whose contour lines (solid) are overlaid with this run's (dashed)")
    ap.add_argument("--compare-steps", default="", help="steps of the comparison " + loaded)
    ap.add_argument("--spacing", default="",
                    help="contour spacing of overlays and comparisons per field, e.g. von_mises=10,stress_xy=10 "
                         "(default: about ten round levels)")
    ap.add_argument("--label", help="this run's name in titles and legends (default: the folder name)")
    ap.add_argument("--compare-label", help="OTHER_OUT's name in the legend (default: its folder name)")
    ap.add_argument("--levels", default="",
                    help="contour levels of maps, overlays and comparisons: a spacing (50) or a list of values "
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
    return ap


def checked_options(args, steps):
    """Every option checked before a figure is drawn: PlotError names the first bad one."""
    fields = [f for f in args.fields.split(",") if f]
    spacing = {}
    for item in (i for i in args.spacing.split(",") if i):
        name, _, value = item.partition("=")
        spacing[name] = number_list("--spacing " + name, value, 1)[0] if value else 0.0
        if spacing[name] <= 0:
            raise PlotError("--spacing %s: expected FIELD=positive value" % item)
    for option, names in (("--fields", fields), ("--spacing", spacing)):
        for name in names:
            if unknown_field(name):
                raise PlotError("%s %s" % (option, unknown_field(name)))
    levels = number_list("--levels", args.levels)
    if levels is not None and len(levels) == 1 and levels[0] <= 0:
        raise PlotError("--levels %s: a spacing must be positive" % args.levels)
    xlim, ylim = number_list("--xlim", args.xlim, 2), number_list("--ylim", args.ylim, 2)
    for name, lim in (("--xlim", xlim), ("--ylim", ylim)):
        if lim is not None and not lim[0] < lim[1]:
            raise PlotError("%s %g,%g: expected LOW,HIGH with LOW < HIGH" % (name, lim[0], lim[1]))
    return fields, spacing, levels, xlim, ylim


def save(fig, path):
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot(args):
    steps = available_steps(args.out)
    if not steps:
        raise PlotError("no step_NNNN.vtu in %s (was the run made with output.vtu = true?)" % args.out)
    fields, spacing, levels, xlim, ylim = checked_options(args, steps)
    last, has_contact = steps[-1], os.path.exists(os.path.join(args.out, "contact.csv"))
    # The default step: the last written one whose roller carries load (a pass run ends lifted).
    loaded = loaded_rows(args.out)
    shown = max([s for s in steps if s in loaded], default=last)
    map_steps = parse_steps("--steps", args.steps, steps) or [shown]
    groups, mesh_groups = step_groups("--pairs", args.pairs, steps), step_groups("--mesh-pairs", args.mesh_pairs, steps)
    profile_steps = parse_steps("--profile-steps", args.profile_steps, steps) or steps
    contact_steps = sorted({int(r["step"]) for r in read_contact(args.out)}) if has_contact else []
    loaded_contact = [s for s in contact_steps if s in loaded] or contact_steps
    pressure_steps = parse_steps("--pressure-steps", args.pressure_steps, contact_steps) or loaded_contact[-1:]
    mesh_steps = parse_steps("--mesh-steps", args.mesh_steps, steps)
    marks = [int(v) for v in number_list("--mark-nodes", args.mark_nodes) or []]
    compare_steps = []
    if args.compare:
        compare_steps = parse_steps("--compare-steps", args.compare_steps, steps) or [shown]
        parse_steps("--compare-steps (of %s)" % args.compare, ",".join(map(str, compare_steps)),
                    available_steps(args.compare))
    hertz = hertz_figure(args.out, args.hertz_step) if args.hertz or args.hertz_step is not None else None
    figs = os.path.join(args.out, "figures")
    os.makedirs(figs, exist_ok=True)
    if hertz:
        save(hertz, os.path.join(figs, "hertz.png"))
    window = None
    if xlim or ylim:
        points = read_vtu(vtu_path(args.out, last)).points
        window = (xlim or strip_window(points)[0], ylim or strip_window(points)[1])
    contour_maps(args.out, figs, map_steps, fields or MAP_FIELDS, levels, args.values == "element", window,
                 args.whole)
    label = args.label or os.path.basename(os.path.normpath(args.out))
    step_overlays(args.out, figs, groups, fields or STRESSES, label, spacing, levels)
    if args.compare:
        other_label = args.compare_label or os.path.basename(os.path.normpath(args.compare))
        run_comparison(args.out, args.compare, figs, compare_steps, fields or STRESSES, label, other_label,
                       spacing, levels)
        if has_contact and os.path.exists(os.path.join(args.compare, "contact.csv")):
            pressure_comparison(args.out, args.compare, figs, compare_steps, label, other_label)
    profile(args.out, figs, profile_steps)
    if has_contact:
        pressure(args.out, figs, pressure_steps)
    if os.path.exists(os.path.join(args.out, "roller.csv")):
        save(forces.forces_figure(args.out, label), os.path.join(figs, "forces.png"))
    if mesh_steps:
        deformed_mesh(args.out, figs, mesh_steps, marks)
    for group in mesh_groups:
        mesh_overlay(args.out, figs, group, marks)
    return figs


def main(argv=None):
    args = arguments().parse_args(argv)
    try:
        figs = plot(args)
    except PlotError as e:
        sys.exit("plot-scene: %s" % e)
    print("plot-scene: figures in %s" % figs)
