"""Stationary passes against long transient passes (docs/validation.md, "Stationary passes
against transient passes"). The shakedown strip at one load (make-shakedown-scenes) is rolled
over a long track, so that the transient pass reaches its steady state, at one element size h:
- the transient method at several step lengths (its error: the steps);
- the stationary pass with the roller's contact, the roller's centre at several places between
  two nodes (its error: the contact resolved at nodes that stand still under the roller), and
  with --stationary-phases P at P such places together, as the transient in steps of h/P meets them;
- the stationary pass with the Hertz load.
With --traction Q/P --friction MU the roller rolls under the horizontal force Q = Q/P x P along the
travel: the transient's exact contact with Coulomb friction against the stationary passes with
Carter's traction (docs/model.md, Stationary pass) on the Hertz pressure or on the roller's
frictionless contact.
Every pass of a transient run is measured on the same stretch of its fields, from 10a to 4a before
the end of the track (14a to 20a past the press on a 24a track: past the start's transient, clear
of where the roller stops), down to 4a (with --periodic, the transient runs on a periodic strip of
one period, the track, 48a unless --track says otherwise, docs/model.md, Periodic strip, and is
measured on the half of the period opposite the press, its passes.csv window: the start and the
end of the ring's rolled layer stress that half, a 24a ring's residual sigma_xx by 10-25 MPa more
than a 48a ring's, docs/validation.md, The ring's length; with --continuous the ring is pressed once and rolled
on, make-shakedown-scenes --continuous, and every period is measured on the half of the ring
opposite the roller, whose elastic field the differences over a period and the long track's
residual sigma_xx do not hold, but the residual sigma_xx as read does): the mean increment of
equivalent plastic strain, its depth integral, the band's at 0.78a and its net shear, the residual
sigma_xx by depth (row means). The
stationary runs' residual strips are uniform along x; they are measured on their own window
(passes.csv), where their displacement is the pass's.

usage: ./rollerpy stationary-check [--load 4.5] [--element-size 0.4] [--steps 0.2,0.1,0.05]
                                   [--phases 0,0.25,0.5] [--stationary-phases 2,4,2:1]
                                   [--reference RUN | endless] [--shorter-ring DIR]
                                   [--track 24 | 48 periodic] [--passes 2]
                                   [--kinematic E_T] [--periodic [--continuous]] [--set KEY=VALUE ...]
                                   [--traction Q/P --friction MU]
                                   [--out out/stationary_check/hH] [--transients-from DIR]
                                   [--roller ./build/roller] [--timeout 14400]

A run whose summary.json says completed is not run again (remove its folder to rerun it).
--transients-from DIR links the transient runs of an earlier check with the same options into OUT,
so that only the stationary runs are made: a new build's stationary pass against references that
took hours.
Writes OUT/stationary_check.md (the table, each run against the transient of the shortest step or the
run --reference names;
the residual sigma_xx at a few depths, with the finest transient also read on the middle of its
track, where its ends relieve it least) and OUT/stationary_check.png (pass 1's increment against
the step, or with one step every pass's; the net shear per pass; the surface's horizontal
displacement per pass; the residual sigma_xx by depth
after the last pass, the finest transient's also on the middle of its track). Each run's progress
is in its log beside its folder.
"""
import os
import sys
import tomllib
from dataclasses import dataclass, field

import numpy as np

from ..command import parser
from ..outputs import read_numbers, read_scene, read_summary
from ..paths import ROOT
from ..runner import run, set_options
from ..vtu import available_steps, read_vtu, vtu_path
from .make_shakedown_scenes import A, PRESS_STEPS, write_scenes

PATH_PARTS = 16                # passes.stationary_path_parts' default (kDefaultPathParts)
STRETCH = (10.0, 4.0)          # the measured stretch: from 10a to 4a before the track's end
MIDDLE = 3.0                   # the middle stretch: 3a either side of the track's middle
WINDOW_DEPTH, BAND_DEPTH = 4.0, 0.78
SXX_DEPTHS = (0.45, 0.65, 0.75, 0.85, 1.05, 1.45)  # the residual sigma_xx table's depths [a]


def geometry(vtu):
    """The elements' centroids, areas and heights in the reference configuration."""
    nodes = vtu.reference[:, :2]
    corners = nodes[vtu.elements]
    centroid = corners.mean(axis=1)
    x, y = corners[..., 0], corners[..., 1]
    area = 0.5 * np.abs(np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1))
    return centroid, area, y.max(axis=1) - y.min(axis=1)


def long_track_sxx(vtu, elastic):
    """The residual sigma_xx a long track would hold with these points' plastic strain: on a base
    held in x and y a state uniform along x has no total xx strain and carries no sigma_yy, so
    sigma_xx = -E (ep_xx + nu ep_zz) / (1 - nu^2) (material/long_track_state.hpp). A finite track's
    ends relieve the rolled layer instead, more the shorter the track."""
    young, nu = elastic
    stress, strain = np.asarray(vtu.cell_data["stress"]), np.asarray(vtu.cell_data["strain"])
    sxx, syy, szz = stress[:, 0], stress[:, 1], stress[:, 2]
    plastic_xx = strain[:, 0] - (sxx - nu * (syy + szz)) / young
    plastic_zz = strain[:, 2] - (szz - nu * (sxx + syy)) / young
    return -young * (plastic_xx + nu * plastic_zz) / (1.0 - nu * nu)


def plastic_shear(vtu, elastic):
    """Each element's plastic shear strain 2 ep_xy = 2 eps_xy - sigma_xy / G: the ratchet, which a
    finite track's ends overlay with the elastic shear of the stress they leave (a long track's
    sigma_xy vanishes: there the total shear is the plastic one)."""
    young, nu = elastic
    strain, stress = np.asarray(vtu.cell_data["strain"]), np.asarray(vtu.cell_data["stress"])
    return 2.0 * strain[:, 3] - stress[:, 3] * 2.0 * (1.0 + nu) / young


def stretch_metrics(now, start, x0, x1, a, elastic, period=None):
    """The pass between two fields (Vtu, at its end and its start) on the stretch x0..x1: mean and band increments of
    equivalent plastic strain (area-weighted, elements whose centroid lies in it, to 4a), the
    increment integrated over the depth [mm] (the mean depends on where the rows of a graded
    mesh cut 4a, the integral does not), the band's net shear strain 2 eps_xy over the pass and its
    plastic part (plastic_shear), the surface's horizontal displacement over the pass [mm] (the
    top nodes' mean: the layer's ratchet, the plastic shear integrated over the depth), and the
    residual sigma_xx by depth (the rows' area-weighted means): as read, and the long track's of the
    same plastic strain (long_track_sxx; `elastic` = (E, nu)), which a stationary run's residual
    strip holds already. `period`: a periodic strip's
    ([mesh] periodic), whose elements are taken at their images nearest the stretch."""
    centroid, area, height = geometry(now)
    if period:
        middle = 0.5 * (x0 + x1)
        centroid[:, 0] += period * np.round((middle - centroid[:, 0]) / period)
    top = now.reference[:, 1].max()
    depth = top - centroid[:, 1]
    inside = (centroid[:, 0] >= x0) & (centroid[:, 0] <= x1) & (depth <= WINDOW_DEPTH * a)
    band = inside & (np.abs(depth - BAND_DEPTH * a) <= 0.25 * a)
    increment = np.ravel(now.cell_data["eq_plastic_strain"]) - np.ravel(start.cell_data["eq_plastic_strain"])
    shear = 2.0 * (np.asarray(now.cell_data["strain"])[:, 3] - np.asarray(start.cell_data["strain"])[:, 3])
    plastic = plastic_shear(now, elastic) - plastic_shear(start, elastic)
    sxx = np.asarray(now.cell_data["stress"])[:, 0]
    sxx_long = long_track_sxx(now, elastic)
    # The surface's horizontal displacement over the pass, the ratchet of the layer above the
    # base (the depth integral of the plastic shear on a long track): the top nodes' mean.
    ref = now.reference
    xs = ref[:, 0] + (period * np.round((0.5 * (x0 + x1) - ref[:, 0]) / period) if period else 0.0)
    on_top = (np.abs(ref[:, 1] - top) <= 1e-9 * max(1.0, abs(top))) & (xs >= x0) & (xs <= x1)
    surface_dux = np.mean(now.point_data["displacement"][on_top, 0] - start.point_data["displacement"][on_top, 0])
    rows = np.round(depth[inside], 6)
    profile, profile_long, integral = [], [], 0.0
    for d in np.unique(rows):
        k = rows == d
        weights = area[inside][k]
        profile.append((d, np.average(sxx[inside][k], weights=weights)))
        profile_long.append((d, np.average(sxx_long[inside][k], weights=weights)))
        integral += height[inside][k][0] * np.average(increment[inside][k], weights=weights)
    return {"mean": np.average(increment[inside], weights=area[inside]),
            "integral": integral,
            "band": np.average(increment[band], weights=area[band]),
            "net_shear": np.average(shear[band], weights=area[band]),
            "net_plastic_shear": np.average(plastic[band], weights=area[band]),
            "surface_dux": surface_dux,
            "sxx": np.array(profile),
            "sxx_long": np.array(profile_long)}


def pass_fields(out, passes):
    """The fields at the start and at the end of every pass of a finished run, each read once: of a
    transient run with [passes] the steps that end a pass (its mid-pass fields, output.mid_pass, left
    out), of a stationary run or one pass (a ring rolled on) every written step."""
    scene = read_scene(out)
    by_pass = scene.get("passes", {})
    marched = by_pass.get("count", 1) > 1 and by_pass.get("method", "transient") == "transient"
    steps = [s for s in available_steps(out) if not marched or s % scene["steps"]["count"] == 0]
    if len(steps) != passes + 1:
        sys.exit("stationary-check: %s holds %d field files, not one a pass and the start" % (out, len(steps)))
    return [read_vtu(vtu_path(out, s)) for s in steps]


def ensure_run(roller, scene, out, pairs, timeout):
    """Runs the scene into out unless a completed run is there; exits with its log on failure."""
    if (read_summary(out, missing_ok=True) or {}).get("status") == "completed":
        return
    print("stationary-check: running %s (progress in %s.log)" % (out, out), flush=True)
    result = run([roller, "run", scene, "--out", out, "--overwrite"] + set_options(pairs), out + ".log", timeout)
    if result.exit_code != 0:
        sys.exit("stationary-check: %s failed (exit %s), see %s" % (out, result.exit_code, result.log))


def link_transients(source, out, steps):
    """Links the transient run of every step from an earlier check's folder into out (symbolic
    links, relative), leaving what out holds already; exits when one of them is not there. The
    scenes are written again into out (the same options give the same files), so that nothing is
    written into the earlier check's folder."""
    os.makedirs(out, exist_ok=True)
    for name in ["transient_s%g" % s for s in steps]:
        target, link = os.path.join(source, name), os.path.join(out, name)
        if not os.path.isdir(target):
            held = sorted(n[len("transient_s"):] for n in os.listdir(source)
                          if n.startswith("transient_s") and os.path.isdir(os.path.join(source, n)))
            sys.exit("stationary-check: --transients-from %s holds no %s (its steps: %s)" % (
                source, name, ", ".join(held) or "none"))
        if not os.path.lexists(link):
            os.symlink(os.path.relpath(os.path.abspath(target), os.path.abspath(out)), link)


def endless_ring(shorter, longer):
    """The residual sigma_xx of an endless ring from two rings' (metrics of the same passes and rows):
    as read and as a long track's, each ring's two profiles close in on each other as the ring grows,
    their difference shrinking by a ratio r (0.25-0.3 from 24a to 48a, docs/validation.md, Phases);
    taking r for both gives their common limit, L1 + (L2 - L1) / (1 - r). Where the difference does
    not shrink (r outside [0, 0.9)), the longer ring's two profiles' mean. The other metrics are the
    longer ring's."""
    out = []
    for short, long_ in zip(shorter, longer):
        l1, r1, l2, r2 = (m[key][:, 1] for m in (short, long_) for key in ("sxx_long", "sxx"))
        if short["sxx"].shape != long_["sxx"].shape or not np.allclose(short["sxx"][:, 0], long_["sxx"][:, 0]):
            sys.exit("stationary-check: --shorter-ring: the two rings' rows differ (give the same element size)")
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = (r2 - l2) / (r1 - l1)
        converging = (ratio >= 0.0) & (ratio < 0.9)
        limit = np.where(converging, l1 + (l2 - l1) / (1.0 - np.where(converging, ratio, 0.0)), 0.5 * (l2 + r2))
        metrics = dict(long_)
        metrics["sxx"] = metrics["sxx_long"] = np.column_stack([long_["sxx"][:, 0], limit])
        out.append(metrics)
    return out


def elastic_constants(scene):
    """(E, nu) of a scene file's strip."""
    with open(scene, "rb") as f:
        material = tomllib.load(f)["material"]
    return material["E"], material["nu"]


def sxx_rows(transients, middle, stationaries, as_read=", as read"):
    """The residual sigma_xx table's rows (sxx_table): every transient's as read and a long
    track's, the finest one's track middle as read, the stationary runs' (a long track's)."""
    out = []
    for label, metrics in transients:
        out += [(label + as_read, metrics, "sxx"), (label + ", a long track's", metrics, "sxx_long")]
    if middle:
        out.append((middle[0] + as_read, middle[1], "sxx"))
    return out + [(label, metrics, "sxx_long") for label, metrics in stationaries]


def roller_centre(scene):
    """The roller's starting centre (x, y) [mm] of a scene file: x is where it presses."""
    with open(scene, "rb") as f:
        return tuple(tomllib.load(f)["roller"]["centre"])


def continuous_windows(passes, a, track, press_x, step):
    """A ring rolled on (make-shakedown-scenes --continuous): every period's fields are written with
    the roller PRESS_STEPS steps before where it pressed; the half of the ring opposite it was rolled over
    once in that period. A period's differences hold nothing of the roller's elastic field, there at
    both ends; the first period's start, before the press, has none, but its shear and u_x, odd
    about the roller, cancel over this window, symmetric about the point opposite it."""
    middle = press_x - PRESS_STEPS * step * a + 0.5 * track * a
    return [(middle - 0.25 * track * a, middle + 0.25 * track * a)] * passes


def measured_windows(out, passes, a, track, own, press_x):
    """Where every pass of a run is measured: the transient's steady stretch, or with `own` the
    run's own window (passes.csv): the stationary's, at the extraction column (its residual strip
    is uniform along x), and a periodic transient's, the half of the period opposite the press."""
    if own:
        return [(r["track_start"], r["track_end"]) for r in read_numbers(os.path.join(out, "passes.csv"))]
    end = press_x + track * a
    return [(end - STRETCH[0] * a, end - STRETCH[1] * a)] * passes


def middle_windows(passes, a, track, press_x):
    """The middle of a transient's track, where the track's ends relieve the residual stress least
    (docs/validation.md, "Both methods' discretisations")."""
    middle = press_x + 0.5 * track * a
    return [(middle - MIDDLE * a, middle + MIDDLE * a)] * passes


def measure(fields, windows, a, elastic, period=None):
    """Every pass of a run (its fields, pass_fields) on its window (elastic, period: stretch_metrics)."""
    return [stretch_metrics(fields[k + 1], fields[k], *window, a, elastic, period) for k, window in enumerate(windows)]


def sxx_at(metrics, depth, key="sxx"):
    """The residual sigma_xx (key: as read, sxx, or the long track's, sxx_long) of the row nearest
    to `depth` [mm], and that row's depth."""
    profile = metrics[key]
    k = int(np.argmin(np.abs(profile[:, 0] - depth)))
    return profile[k, 1], profile[k, 0]


def sxx_table(rows, passes, a):
    """The residual sigma_xx [MPa] at a few depths, every run and pass (rows: label, metrics, key
    of sxx_at)."""
    depths = [sxx_at(rows[0][1][0], d * a)[1] for d in SXX_DEPTHS]
    lines = []
    for k in range(passes):
        lines += ["", "Residual σ_xx [MPa] after pass %d, by depth [mm]:" % (k + 1), "",
                  "| run | " + " | ".join("%.2f" % d for d in depths) + " |",
                  "|---|" + "---:|" * len(depths)]
        for label, metrics, key in rows:
            lines.append("| %s | " % label + " | ".join("%.0f" % sxx_at(metrics[k], d, key)[0] for d in depths) + " |")
    return "\n".join(lines) + "\n"


def sxx_gap(run, reference, below=0.0):
    """The largest difference of the long track's residual sigma_xx by depth (rows deeper than
    `below`) over the reference's peak, and the depth where it is."""
    r, s = reference["sxx_long"], run["sxx_long"]
    gap = np.where(r[:, 0] > below, np.abs(s[:, 1] - r[:, 1]), 0.0)
    k = int(np.argmax(gap))
    return gap[k] / np.max(np.abs(r[:, 1])), r[k, 0]


def table(runs, reference, passes):
    lines = ["| run | pass | mean Δε̄ᵖ to 4a | against the reference | ∫Δε̄ᵖ dz [µm] | band at 0.78a | against | "
             "net Δγ_xy in the band | its plastic part | surface Δu_x [µm] | "
             "long track's residual σ_xx: largest gap / peak, at depth | the same below a/2 |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for label, metrics in runs:
        for k in range(passes):
            m, r = metrics[k], reference[k]
            gap, depth = sxx_gap(m, r)
            deep_gap, deep = sxx_gap(m, r, below=0.5 * A)
            lines.append("| %s | %d | %.3e | %+.1f %% | %.2f | %.3e | %+.1f %% | %.2e | %.2e | %.2f | "
                         "%.1f %%, %.2f mm | %.1f %%, %.2f mm |" % (
                             label, k + 1, m["mean"], 100 * (m["mean"] / r["mean"] - 1), 1000 * m["integral"],
                             m["band"], 100 * (m["band"] / r["band"] - 1), m["net_shear"], m["net_plastic_shear"],
                             1000 * m["surface_dux"], 100 * gap, depth, 100 * deep_gap, deep))
    return "\n".join(lines) + "\n"


def figure(path, transients, stationaries, passes, track_middle, label_of_finest=None, as_read=", as read"):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import FormatStrFormatter, MaxNLocator
    styles = ("--", "-.", ":", (0, (5, 1)), (0, (1, 3)))
    fig, (left, middle, surface, right) = plt.subplots(1, 4, figsize=(19, 4.4))
    steps = [s for s, _ in transients]
    numbers = range(1, passes + 1)
    by_step = len(steps) > 1  # pass 1 against the transient's step, else every pass's increment
    if by_step:
        left.plot(steps, [m[0]["mean"] for _, m in transients], "o-k", label="transient")
    if transients:
        finest = label_of_finest
        if not by_step:
            left.plot(numbers, [m["mean"] for m in transients[-1][1]], "o-k", label=finest)
        middle.plot(numbers, [m["net_shear"] for m in transients[-1][1]], "o-k", label=finest)
        surface.plot(numbers, [1000 * m["surface_dux"] for m in transients[-1][1]], "o-k", label=finest)
        p = transients[-1][1][passes - 1]["sxx_long"]
        right.plot(p[:, 1], p[:, 0], "o-k", ms=3, label=finest + ", a long track's")
        p = transients[-1][1][passes - 1]["sxx"]
        right.plot(p[:, 1], p[:, 0], "--", color="0.3", lw=1, label=finest + as_read)
        p = track_middle[1][passes - 1]["sxx"]
        right.plot(p[:, 1], p[:, 0], "-", color="0.55", lw=2.5, label=track_middle[0] + as_read, zorder=0)
    for (label, metrics), style in zip(stationaries, styles):
        colour = "C0" if "roller" in label else "C3"
        if by_step:
            left.axhline(metrics[0]["mean"], ls=style, color=colour, label=label)
        else:
            left.plot(numbers, [m["mean"] for m in metrics], ls=style, color=colour, marker=".", label=label)
        middle.plot(numbers, [m["net_shear"] for m in metrics], ls=style, color=colour, marker=".", label=label)
        surface.plot(numbers, [1000 * m["surface_dux"] for m in metrics], ls=style, color=colour, marker=".",
                     label=label)
        p = metrics[passes - 1]["sxx_long"]
        right.plot(p[:, 1], p[:, 0], ls=style, color=colour, label=label)
    if by_step:
        left.set_xscale("log")
        left.set_xticks(steps)
        left.set_xticklabels(["%g" % v for v in steps])
        left.minorticks_off()
        left.set_xlabel("transient step [a]")
        left.set_ylabel("pass 1: mean Δε̄ᵖ to 4a")
    else:
        left.set_yscale("log")
        left.set_xticks(list(numbers))
        left.set_xlabel("pass")
        left.set_ylabel("mean Δε̄ᵖ to 4a")
    middle.set_yscale("symlog", linthresh=1e-5)
    limits = middle.get_ylim()
    ticks = [t for t in middle.get_yticks() if t == 0.0 or abs(t) >= 1e-5]  # none crowding 0
    if sum(limits[0] <= t <= limits[1] for t in ticks) < 2:  # the values within one decade: linear ticks
        ticks = [t for t in MaxNLocator(4).tick_values(*limits) if limits[0] <= t <= limits[1]]
        middle.yaxis.set_major_formatter(FormatStrFormatter("%.1e"))
    middle.set_yticks(ticks)
    middle.set_ylim(limits)
    middle.axhline(0.0, color="0.6", lw=0.8)
    middle.set_xticks(list(numbers))
    middle.set_xlabel("pass")
    middle.set_ylabel("net Δγ_xy at 0.78a (+: along the travel)")
    surface.set_yscale("symlog", linthresh=0.1)
    surface.axhline(0.0, color="0.6", lw=0.8)
    surface.set_xticks(list(numbers))
    surface.set_xlabel("pass")
    surface.set_ylabel("surface Δu_x over the pass [µm] (+: along the travel)")
    right.invert_yaxis()
    right.set_xlabel("residual σ_xx after pass %d [MPa]" % passes)
    right.set_ylabel("depth [mm]")
    for ax in (left, middle, surface, right):
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


@dataclass
class TransientRuns:
    """The transient runs, coarsest step first, and what the later steps take from the finest one: its
    fields and press (read again on the track's middle), its scene (the stationary runs' on a track
    with ends) and its strip's elastic constants."""
    by_step: list = field(default_factory=list)  # (step [a], metrics of every pass)
    rows: list = field(default_factory=list)     # (label, metrics): the table's rows
    fields: list = None                          # the finest run's (pass_fields)
    scene: str = None                            # the finest run's scene file
    centre: tuple = None                         # its roller's starting centre (x, y) [mm]
    elastic: tuple = None                        # its strip's (E, nu)

    @property
    def finest_step(self):
        return self.by_step[-1][0]


def parse_arguments(argv):
    """The options, with the track's default filled in; exits on options that do not go together."""
    ap = parser("stationary-check", __doc__)
    load = ap.add_argument_group("load and mesh")
    load.add_argument("--load", type=float, default=4.5, help="p0/k")
    load.add_argument("--element-size", type=float, default=0.4)
    load.add_argument("--track", type=float, default=None,
                      help="the track's length in a (default 24; with --periodic, the ring's period, default 48: a "
                           "shorter ring's own rolled layer biases the reference; docs/validation.md, The ring's "
                           "length)")
    load.add_argument("--passes", type=int, default=2)
    load.add_argument("--kinematic", type=float, default=None, metavar="E_T")
    load.add_argument("--traction", type=float, default=None, metavar="Q/P",
                      help="roll under the horizontal force Q = Q/P x P (Carter's traction on the stationary pass; "
                           "needs --friction)")
    load.add_argument("--friction", type=float, default=0.0)
    load.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                      help="a scene value for every run (roller run --set), e.g. another hardening law")
    transient = ap.add_argument_group("transient runs")
    transient.add_argument("--steps", default="0.2,0.1,0.05",
                           help="the transient's steps, in a; none: the stationary runs alone, against the first")
    transient.add_argument("--transients-from", default=None, metavar="DIR",
                           help="an earlier check's folder whose transient runs OUT links, not runs")
    stationary = ap.add_argument_group("stationary runs")
    stationary.add_argument("--phases", default="0,0.25,0.5", help="the roller's centre past a node, in elements")
    stationary.add_argument("--stationary-phases", default="", metavar="P[:N][,P[:N]]",
                            help="also the stationary pass solved at P places of the roller between two nodes "
                                 "together (passes.stationary_phases = P; docs/model.md, Phases), its yielding steps "
                                 "walked in N parts (passes.stationary_path_parts, default 16; 1: the transient's "
                                 "steps of h/P)")
    ring = ap.add_argument_group("ring (periodic strips)")
    ring.add_argument("--periodic", action="store_true",
                      help="the transient runs on a periodic strip of one track's period (no track ends)")
    ring.add_argument("--continuous", action="store_true",
                      help="with --periodic: the ring pressed once and rolled on --passes periods")
    ring.add_argument("--shorter-ring", default=None, metavar="DIR",
                      help="with --periodic: an earlier check's folder with a shorter ring (the same options but "
                           "--track), whose transient of the shortest step gives, with this one's, the endless "
                           "ring's residual sigma_xx (a row of the table; --reference endless makes it the reference)")
    output = ap.add_argument_group("output and program")
    output.add_argument("--reference", default=None, metavar="RUN",
                        help="the run the table is made against: a run's folder name in OUT (e.g. "
                             "stationary_roller_P8_n1); default the transient of the shortest step")
    output.add_argument("--out", default=None)
    output.add_argument("--roller", default="./build/roller")
    output.add_argument("--timeout", type=float, default=14400.0)
    args = ap.parse_args(argv)
    if args.shorter_ring and (not args.periodic or args.continuous or args.steps == "none"):
        sys.exit("stationary-check: --shorter-ring extrapolates two periodic rings: give --periodic and --steps")
    if args.continuous and not args.periodic:
        sys.exit("stationary-check: --continuous rolls a ring: give --periodic too")
    if args.passes < 2:  # a one-pass run writes no passes.csv, whose windows the check measures
        sys.exit("stationary-check: --passes %d: the check compares passes: give at least 2" % args.passes)
    if args.track is None:
        args.track = 48.0 if args.periodic else 24.0
    if args.track < 2.0 * STRETCH[0]:
        sys.exit("stationary-check: --track %g: the measured stretch starts %ga before the end, give at least %ga" % (
            args.track, STRETCH[0], 2.0 * STRETCH[0]))
    return args


def transient_steps(spec):
    """--steps as step lengths [a], longest first; none: no transient runs."""
    return [] if spec == "none" else sorted((float(s) for s in spec.split(",")), reverse=True)


def scene_pairs(items):
    """--set's KEY=VALUE items as (key, value) pairs; exits on one without '='."""
    pairs = [tuple(item.split("=", 1)) for item in items]
    if any(len(pair) != 2 for pair in pairs):
        sys.exit("stationary-check: --set takes KEY=VALUE")
    return pairs


def run_transients(args, steps, roller, out, common, period):
    """Runs the transient of every step (unless completed) and measures its passes."""
    transients = TransientRuns()
    kind = ", ring rolled on" if args.continuous else ", periodic" if args.periodic else ""
    for s in steps:
        scene, = write_scenes([args.load], args.passes, args.element_size, os.path.join(out, "scenes_s%g" % s),
                              args.kinematic, args.track, s, args.periodic, args.continuous, args.traction,
                              args.friction)
        press_x, centre_y = roller_centre(scene)
        elastic = elastic_constants(scene)
        run_out = os.path.join(out, "transient_s%g" % s)
        ensure_run(roller, scene, run_out, common, args.timeout)
        fields = pass_fields(run_out, args.passes)
        if args.continuous:
            windows = continuous_windows(args.passes, A, args.track, press_x, s)
        else:
            windows = measured_windows(run_out, args.passes, A, args.track, args.periodic, press_x)
        metrics = measure(fields, windows, A, elastic, period)
        transients.by_step.append((s, metrics))
        transients.rows.append(("transient%s, step %ga" % (kind, s), metrics))
        transients.fields, transients.scene, transients.centre, transients.elastic = (
            fields, scene, (press_x, centre_y), elastic)
        print("stationary-check: transient, step %ga: pass 1 %.4e" % (s, metrics[0]["mean"]))
    return transients


def endless_ring_row(args, transients):
    """The endless ring's row (label, metrics): the shorter ring's (--shorter-ring) transient of the
    finest step and this check's, extrapolated (endless_ring)."""
    step = transients.finest_step
    run_short = os.path.join(args.shorter_ring, "transient_s%g" % step)
    with open(os.path.join(run_short, "scene.resolved.toml"), "rb") as f:
        short_track = tomllib.load(f)["mesh"]["length"] / A
    shorter = measure(pass_fields(run_short, args.passes),
                      measured_windows(run_short, args.passes, A, short_track, True, 0.0), A, transients.elastic,
                      A * short_track)
    return ("transient, periodic, step %ga, endless ring (σ_xx from the %ga and %ga rings; the rest the %ga's)"
            % (step, short_track, args.track, args.track), endless_ring(shorter, transients.by_step[-1][1]))


def stationary_scene(args, out, transients):
    """The stationary runs' scene and its roller's centre (x, y): on a track with ends the finest
    transient's, else one of their own, a strip with ends (the step does not enter a stationary pass)."""
    if transients.by_step and not args.periodic:
        return transients.scene, transients.centre
    scene, = write_scenes([args.load], args.passes, args.element_size, os.path.join(out, "scenes"), args.kinematic,
                          args.track, traction=args.traction, friction=args.friction)
    press_x, centre_y = roller_centre(scene)
    return scene, (press_x, centre_y)


def stationary_variants(args, press_x, centre_y, h):
    """The stationary runs as (label, scene pairs, folder name): the roller's contact with its centre
    moved along x by a fraction of an element (--phases), at P phases together (--stationary-phases),
    and the Hertz load."""
    variants = [("stationary, roller, centre +%gh" % p, [("passes.stationary_contact", '"roller"'),
                 ("roller.centre", "[%r, %r]" % (press_x + p * h, centre_y))], "stationary_roller_ph%g" % p)
                for p in (float(v) for v in args.phases.split(",") if v)]
    for item in (v for v in args.stationary_phases.split(",") if v):
        p, n = (int(x) for x in (item.split(":") + [str(PATH_PARTS)])[:2])
        parts = "" if n == PATH_PARTS else ", %d part%s" % (n, "" if n == 1 else "s")
        variants.append(("stationary, roller, %d phases%s" % (p, parts),
                         [("passes.stationary_contact", '"roller"'), ("passes.stationary_phases", "%d" % p),
                          ("passes.stationary_path_parts", "%d" % n)],
                         "stationary_roller_P%d%s" % (p, "" if n == PATH_PARTS else "_n%d" % n)))
    variants.append(("stationary, Hertz load", [("passes.stationary_contact", '"hertz"')], "stationary_hertz"))
    return variants


def check_reference(reference, names, endless):
    """Exits unless --reference names one of the stationary runs' folders, or endless with its row;
    checked before the stationary runs, which can take hours."""
    if reference and reference not in names and not (reference == "endless" and endless):
        sys.exit("stationary-check: --reference %s: not one of this check's stationary runs (%s)%s" % (
            reference, ", ".join(names), ", nor endless (with --shorter-ring)" if endless else ""))


def run_stationaries(args, roller, scene, out, common, press_x, variants):
    """Runs every stationary variant (unless completed) and measures its passes on its own window;
    returns (label, metrics) in the variants' order."""
    stationary = [("passes.method", '"stationary"'), ("output.every", "1")]  # fields after every pass
    elastic = elastic_constants(scene)
    stationaries = []
    for label, pairs, name in variants:
        run_out = os.path.join(out, name)
        ensure_run(roller, scene, run_out, common + stationary + pairs, args.timeout)
        metrics = measure(pass_fields(run_out, args.passes),
                          measured_windows(run_out, args.passes, A, args.track, True, press_x), A, elastic)
        stationaries.append((label, metrics))
        print("stationary-check: %s: pass 1 %.4e" % (label, metrics[0]["mean"]))
    return stationaries


def track_middle(args, transients, period):
    """The finest transient read on the middle of its track (label, metrics), None without transients."""
    if not transients.by_step:
        return None
    windows = middle_windows(args.passes, A, args.track, transients.centre[0])
    return ("transient, step %ga, the track's middle (%ga either side)" % (transients.finest_step, MIDDLE),
            measure(transients.fields, windows, A, transients.elastic, period))


def pick_reference(reference, transients, endless, stationaries, names):
    """The row (label, metrics) the table is made against: --reference's, else the transient of the
    shortest step, else the first stationary run."""
    if reference == "endless" and endless:
        return endless[0]
    if reference:
        return stationaries[names.index(reference)]
    return transients.rows[-1] if transients.rows else stationaries[0]


def write_report(args, out, transients, endless, stationaries, middle, reference):
    """OUT/stationary_check.md (the table and the residual sigma_xx by depth) and OUT/stationary_check.png."""
    rows = transients.rows + endless + stationaries
    as_read = ", as read, roller on" if args.continuous else ", as read"  # its elastic field in it
    report = os.path.join(out, "stationary_check.md")
    with open(report, "w") as f:
        f.write("p0/k = %g, h = %g mm, track %ga; the reference: the %s\n\n" % (
            args.load, args.element_size, args.track, reference[0]))
        f.write(table(rows, reference[1], args.passes))
        f.write(sxx_table(sxx_rows(transients.rows, middle, endless + stationaries, as_read), args.passes, A))
    figure(os.path.join(out, "stationary_check.png"), transients.by_step, stationaries, args.passes, middle,
           transients.rows[-1][0] if transients.rows else None, as_read)
    print("stationary-check: wrote %s" % report)


def main(argv=None):
    args = parse_arguments(argv)
    os.chdir(ROOT)
    roller = os.path.abspath(args.roller)
    out = args.out or os.path.join("out", "stationary_check", "h%g" % args.element_size)
    steps = transient_steps(args.steps)
    common = scene_pairs(args.set)
    if args.transients_from:
        link_transients(args.transients_from, out, steps)
    period = A * args.track if args.periodic else None
    transients = run_transients(args, steps, roller, out, common, period)
    endless = [endless_ring_row(args, transients)] if args.shorter_ring else []
    scene, (press_x, centre_y) = stationary_scene(args, out, transients)
    variants = stationary_variants(args, press_x, centre_y, args.element_size)
    names = [name for _, _, name in variants]  # the stationary runs' folders, in their order
    check_reference(args.reference, names, endless)
    stationaries = run_stationaries(args, roller, scene, out, common, press_x, variants)
    reference = pick_reference(args.reference, transients, endless, stationaries, names)
    write_report(args, out, transients, endless, stationaries, track_middle(args, transients, period), reference)
    return 0
