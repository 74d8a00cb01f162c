"""Figures (PNG) of a multi-pass run: what each pass left in the strip.

usage: ./rollerpy plot-passes OUT_DIR [--compare OUT_DIR2 ...]

Reads OUT_DIR/passes.csv, residual_depth.csv and summary.json (docs/scenes.md, Outputs) and
writes into OUT_DIR:
  passes.png          per pass, on a log axis: the increment of equivalent plastic strain in the
                      track window (max and area mean), in the band at the depth of maximum shear,
                      the net residual shear strain increment there, and the permanent settlement
                      |du_y| of the mid-track surface; the verdict of summary.json in the title
  residual_depth.png  residual stresses sigma_xx, sigma_zz (the out-of-plane one) and sigma_xy,
                      the equivalent plastic strain and, with a kinematic law, the back-stress
                      sum alpha_xx under the middle of the track against depth, one curve per pass
  fatigue.png         with [fatigue] (fatigue.csv): Dang Van's index and Ekberg's FI_sub/tau_e
                      against depth, one curve per pass, the limit 1 marked; FI_surf and Kapoor's
                      ratchetting life of the last pass (summary.json) in the title
  ratchet.png         with --compare: the net residual shear strain increment per pass (signed:
                      positive when the material above that depth moved in +x, the roller's
                      travel, relative to the material below) and the
                      mean plastic strain increment per pass of OUT_DIR and each compared run,
                      labelled with the scene and its hardening law
Needs numpy and matplotlib from Debian (python3-numpy, python3-matplotlib).
"""
import os
import tomllib
from dataclasses import dataclass

from matplotlib.ticker import FixedLocator, FormatStrFormatter, MaxNLocator, NullFormatter

from ..command import parser
from ..outputs import read_numbers, read_summary
from . import plt


def positive(values):
    """Values for a log axis: zeros and negatives are not drawn."""
    return [v if v > 0 else float("nan") for v in values]


def plot_passes(out, rows, title):
    passes = [int(r["pass"]) for r in rows]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    series = [
        ("max_plastic_increment", "max Δε̄ᵖ in the track window", "o-"),
        ("mean_plastic_increment", "mean Δε̄ᵖ in the track window", "s-"),
        ("band_plastic_increment", "mean Δε̄ᵖ at the depth of max shear", "^-"),
    ]
    for key, label, style in series:
        ax.semilogy(passes, positive([r[key] for r in rows]), style, label=label)
    ax.semilogy(passes, positive([abs(r["residual_shear_increment"]) for r in rows]), "v--",
                label="|net Δγ_xy| at the depth of max shear")
    ax.semilogy(passes, positive([abs(r["surface_duy"]) for r in rows]), "d:",
                label="|Δu_y| of the mid-track surface [mm]")
    ax.set_xlabel("pass")
    ax.set_ylabel("increment over the pass")
    ax.set_xticks(passes)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "passes.png"), dpi=150)
    plt.close(fig)


@dataclass
class DepthPanels:
    """What residual_depth.png draws: the columns (keys) with their axis labels, a note for the
    title, the depth the axis reaches."""
    keys: list
    labels: list
    note: str
    depth: float


def depth_panels(rows, cap):
    """The panels of residual_depth.csv's rows. σ_xy is left out where it vanishes: a long track's
    residual state is uniform along x (a stationary run's always), and an empty panel says nothing.
    The depth axis reaches 1.5 times the depth beyond which every quantity stays below 2 % of its
    largest (what the passes left lies above it), at most `cap` and the strip's depth."""
    keys = ["sxx", "szz", "sxy", "eq_plastic_strain"]
    labels = ["residual σ_xx [MPa]", "residual σ_zz [MPa]", "residual σ_xy [MPa]", "ε̄ᵖ"]
    if any(r.get("back_xx", 0.0) != 0.0 for r in rows):  # a kinematic law: the yield surface's centre
        keys.append("back_xx")
        labels.append("back-stress Σα_xx [MPa]")
    largest = {k: max(abs(r[k]) for r in rows) for k in keys}
    note = ""
    if largest["sxy"] <= 1e-3 * max(largest["sxx"], largest["szz"]):
        del labels[keys.index("sxy")]
        keys.remove("sxy")
        size = "= 0" if largest["sxy"] == 0.0 else "≈ 0 (|σ_xy| ≤ %.2g MPa)" % largest["sxy"]
        note = "residual σ_xy %s, not drawn: the residual state is uniform along the track" % size
    deepest = max(r["depth"] for r in rows)
    reached = [r["depth"] for r in rows for k in keys if largest[k] > 0.0 and abs(r[k]) > 0.02 * largest[k]]
    depth = min(deepest, cap, 1.5 * max(reached)) if reached else min(deepest, cap)
    return DepthPanels(keys, labels, note, depth)


def plot_depth(out, rows, title):
    passes = sorted({int(r["pass"]) for r in rows})
    panels = depth_panels(rows, 8.0 * max(1e-9, _half_width(out)))
    fig, axes = plt.subplots(1, len(panels.keys), figsize=(3 * len(panels.keys), 4.5), sharey=True)
    colours = plt.cm.viridis([i / max(1, len(passes) - 1) for i in range(len(passes))])
    for colour, p in zip(colours, passes):
        sel = [r for r in rows if int(r["pass"]) == p]
        depth = [r["depth"] for r in sel]
        for ax, key in zip(axes, panels.keys):
            ax.plot([r[key] for r in sel], depth, color=colour, label="pass %d" % p)
    for ax, label in zip(axes, panels.labels):
        ax.set_xlabel(label)
        ax.grid(True, alpha=0.3)
        ax.xaxis.set_major_locator(MaxNLocator(nbins=4))  # labels that do not run together
        ax.ticklabel_format(axis="x", style="sci", scilimits=(-3, 4))
    axes[0].set_ylim(panels.depth, 0.0)
    axes[0].set_ylabel("depth below the surface [mm]")
    axes[-1].legend(fontsize=8)
    fig.suptitle(title + ("\n" + panels.note if panels.note else ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "residual_depth.png"), dpi=150)
    plt.close(fig)


def fatigue_title(title, fatigue):
    """The figure's title with the last pass's surface index and ratchetting life (summary.json)."""
    if not fatigue:
        return title
    life = fatigue.get("ratchetting_life")
    life_text = "no surface ratchet" if life is None else "%.3g passes to ratchetting failure" % life
    surface = fatigue.get("surface_index")
    surface_text = "FI_surf %.3g" % surface if surface is not None else "no contact"
    return "%s\npass %d: %s (f = %.3g, k/p0 = %.3g), %s" % (
        title, fatigue["pass"], surface_text, fatigue["traction_coefficient"],
        fatigue["shear_yield"] / fatigue["peak_pressure"] if fatigue["peak_pressure"] > 0 else 0.0, life_text)


def plot_fatigue(out, rows, title, fatigue):
    """fatigue.png: the two subsurface indices against depth, one curve per pass."""
    passes = sorted({int(r["pass"]) for r in rows})
    panels = [("dang_van_index", "Dang Van: max (τ + a σ_h) / τ_w"), ("fi_sub_index", "Ekberg: FI_sub / τ_e")]
    fig, axes = plt.subplots(1, 2, figsize=(8, 5), sharey=True)
    colours = plt.cm.viridis([i / max(1, len(passes) - 1) for i in range(len(passes))])
    for colour, p in zip(colours, passes):
        sel = [r for r in rows if int(r["pass"]) == p]
        for ax, (key, _) in zip(axes, panels):
            ax.plot([r[key] for r in sel], [r["depth"] for r in sel], color=colour, label="pass %d" % p)
    for ax, (_, label) in zip(axes, panels):
        ax.axvline(1.0, color="r", lw=1.0, ls="--")
        ax.set_xlabel(label + "\n(> 1: initiation)")
        ax.grid(True, alpha=0.3)
    # Depth on a log axis: the surface's rows, where rolling contact initiates, beside the decay
    # below; down to where the indices have fallen to a tenth of their largest.
    largest = max(max(r["dang_van_index"], r["fi_sub_index"]) for r in rows)
    reached = [r["depth"] for r in rows if max(r["dang_van_index"], r["fi_sub_index"]) > 0.1 * largest]
    axes[0].set_yscale("log")
    axes[0].yaxis.set_major_locator(FixedLocator([0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50, 100, 200, 500]))
    axes[0].yaxis.set_major_formatter(FormatStrFormatter("%g"))
    axes[0].yaxis.set_minor_formatter(NullFormatter())
    axes[0].set_ylim(min(max(r["depth"] for r in rows), 1.2 * max(reached)), 0.8 * min(r["depth"] for r in rows))
    axes[0].set_ylabel("depth below the surface [mm] (element centres)")
    axes[-1].legend(fontsize=8)
    fig.suptitle(fatigue_title(title, fatigue), fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fatigue.png"), dpi=150)
    plt.close(fig)


def _half_width(out):
    rows = read_numbers(os.path.join(out, "passes.csv"))
    return max(r["contact_half_width"] for r in rows) if rows else 1.0


def plot(out):
    """passes.png, residual_depth.png and (with fatigue.csv) fatigue.png of the run in `out`;
    returns their paths."""
    summary = read_summary(out) if os.path.exists(os.path.join(out, "summary.json")) else {}
    passes = summary.get("passes", {})
    title = "%s: %s" % (summary.get("scene", out), passes.get("verdict", "").replace("_", " "))
    if "p0_over_k" in passes:
        title += " (p0/k = %.2f)" % passes["p0_over_k"]
    plot_passes(out, read_numbers(os.path.join(out, "passes.csv")), title)
    plot_depth(out, read_numbers(os.path.join(out, "residual_depth.csv")), title)
    written = [os.path.join(out, "passes.png"), os.path.join(out, "residual_depth.png")]
    fatigue_csv = os.path.join(out, "fatigue.csv")
    if os.path.exists(fatigue_csv):
        plot_fatigue(out, read_numbers(fatigue_csv), title, summary.get("fatigue"))
        written.append(os.path.join(out, "fatigue.png"))
    return written


def run_label(out):
    """'scene, hardening law, how the passes were solved' of a run, from its resolved scene."""
    try:
        with open(os.path.join(out, "scene.resolved.toml"), "rb") as f:
            scene = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError):
        return os.path.basename(os.path.normpath(out))
    material = scene.get("material", {})
    law = material.get("hardening", "elastic" if "yield_stress" not in material else "isotropic")
    if law == "chaboche":
        law += " C=%s γ=%s" % (material.get("chaboche_C"), material.get("chaboche_gamma"))
    elif law in ("isotropic", "kinematic", "mixed"):
        law += " E_T=%g" % material.get("tangent_modulus", 0.0)
    passes = scene.get("passes", {})
    if passes.get("method") == "stationary":
        contact = passes.get("stationary_contact", "roller")
        method = "stationary, " + ("Hertz load" if contact == "hertz" else "roller's contact")
    else:
        method = scene.get("contact", {}).get("backend", "")
    return ", ".join(x for x in (scene.get("name", out), law, method) if x)


def plot_ratchet(outs, path):
    """ratchet.png: the runs' net shear strain increment and mean plastic increment per pass."""
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    for out in outs:
        rows = read_numbers(os.path.join(out, "passes.csv"))
        passes = [int(r["pass"]) for r in rows]
        label = run_label(out)
        top.plot(passes, [r["residual_shear_increment"] for r in rows], "o-", label=label)
        bottom.semilogy(passes, positive([r["mean_plastic_increment"] for r in rows]), "s-", label=label)
    top.axhline(0.0, color="k", lw=0.8)
    # Signed and over decades (a slow ratchet's 1e-5 beside pass 1's 1e-3): linear below 1e-6.
    top.set_yscale("symlog", linthresh=1e-6)
    top.set_ylabel("net Δγ_xy over the pass\nat the depth of max shear")
    bottom.set_ylabel("mean Δε̄ᵖ over the pass\nin the track window")
    bottom.set_xlabel("pass")
    for ax in (top, bottom):
        ax.grid(True, which="both", alpha=0.3)
    top.legend(fontsize=8)
    top.set_title("ratchetting per pass (positive: the layer above moved along the roller's travel, +x)",
                  fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)
    return path


def main(argv=None):
    ap = parser("plot-passes", __doc__)
    ap.add_argument("out")
    ap.add_argument("--compare", nargs="+", default=[], metavar="OUT_DIR",
                    help="other multi-pass runs drawn beside OUT_DIR in ratchet.png")
    args = ap.parse_args(argv)
    print("wrote", ", ".join(plot(args.out)))
    if args.compare:
        print("wrote", plot_ratchet([args.out] + args.compare, os.path.join(args.out, "ratchet.png")))
