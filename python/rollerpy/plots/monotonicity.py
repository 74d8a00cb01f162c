"""PNG maps of the positive definiteness of operator A (thesis Fig. 3.1 a-l; docs/monotonicity.md).

usage: ./rollerpy plot-monotonicity OUT_DIR
Reads OUT_DIR/monotonicity.json, monotonicity_slices.csv and monotonicity_grid.csv written by
`roller monotonicity` and writes into OUT_DIR:
  fig3_1_<panel>.png      one map per panel a-l
  fig3_1_overview.png     the twelve panels together
  fig3_1_sigma_layers.png panel a (c = 0) for every sigma_pl layer of the 4-D grid

Each map: colour = lambda_min(A) / 2G (the thesis's normalisation, elastic value 1/2; clipped to
[-1/2, 1/2]), black line = lambda_min = 0 on the fine slice, + / - = the thesis's presentation on
the grid's own points (PD / not PD), red = the yield curve f = 0 at the slice's sigma_pl (von
Mises of the full deviator, t33 as chosen), orange dashed = the curve the thesis's captions use,
sqrt(I2) = sigma_pl with I2 = 1/2 (s11^2 + s22^2 + 2 s12^2), s11 = a/3, s22 = b/3, s12 = c
(found from the captions' numbers, see docs/monotonicity.md).
Needs numpy and matplotlib (the system python has them).
"""
import json
import os

import numpy as np

from ..command import parser
from ..outputs import read_array
from . import plt

AXIS_LABEL = {"a": "a = 2τ11 − τ22 [MPa]", "b": "b = 2τ22 − τ11 [MPa]", "c": "c = τ12 [MPa]"}


def stress(a, b, c, tau33_rule, nu):
    t11 = (2 * a + b) / 3.0
    t22 = (2 * b + a) / 3.0
    t33 = 0.0 * a if tau33_rule == "zero" else nu * (t11 + t22)
    return t11, t22, t33, c + 0.0 * a


def von_mises(a, b, c, tau33_rule, nu):
    t11, t22, t33, t12 = stress(a, b, c, tau33_rule, nu)
    m = (t11 + t22 + t33) / 3.0
    ss = (t11 - m) ** 2 + (t22 - m) ** 2 + (t33 - m) ** 2 + 2 * t12 ** 2
    return np.sqrt(1.5 * ss)


def thesis_sqrt_i2(a, b, c):
    return np.sqrt(0.5 * ((a / 3.0) ** 2 + (b / 3.0) ** 2 + 2 * c ** 2))


def slice_axes(plane):
    """(horizontal, vertical, fixed) parameter names of a slice plane."""
    return {"ab": ("a", "b", "c"), "ca": ("a", "c", "b"), "cb": ("b", "c", "a")}[plane]


def draw_panel(ax, meta, panel, slices, small=False):
    pid = panel["id"]
    h, v, fixed = slice_axes(panel["plane"])
    sel = slices[slices["panel"] == pid]
    fine = sel[sel["resolution"] == "fine"]
    coarse = sel[sel["resolution"] == "coarse"]
    n = meta["slice_grid"]
    two_g = 2.0 * meta["G"]
    x = fine[h].reshape(n, n)
    y = fine[v].reshape(n, n)
    lam = fine["lambda_min"].reshape(n, n) / two_g
    mesh = ax.pcolormesh(x, y, np.clip(lam, -0.5, 0.5), cmap="RdBu", vmin=-0.5, vmax=0.5,
                         shading="auto")
    if lam.min() < 0 < lam.max():
        ax.contour(x, y, lam, levels=[0.0], colors="k", linewidths=1.2)
    pd = coarse["pd_eigen"] == 1
    ms = 3 if small else 6
    ax.plot(coarse[h][pd], coarse[v][pd], "+", color="k", ms=ms, mew=0.8, ls="none")
    ax.plot(coarse[h][~pd], coarse[v][~pd], "_", color="0.35", ms=ms, mew=0.8, ls="none")
    # Yield curves on a fine grid of the plane.
    hx = np.linspace(x.min(), x.max(), 600)
    vy = np.linspace(y.min(), y.max(), 600)
    hh, vv = np.meshgrid(hx, vy, indexing="ij")
    p = {h: hh, v: vv, fixed: panel["fixed"] + 0.0 * hh}
    sigma = meta["slice_sigma"]
    vm = von_mises(p["a"], p["b"], p["c"], meta["tau33"], meta["nu"])
    if vm.min() < sigma < vm.max():
        ax.contour(hh, vv, vm, levels=[sigma], colors="red", linewidths=1.6)
    yi2 = thesis_sqrt_i2(p["a"], p["b"], p["c"])
    if yi2.min() < sigma < yi2.max():
        ax.contour(hh, vv, yi2, levels=[sigma], colors="orange", linewidths=1.4,
                   linestyles="--")
    ax.set_xlim(x.min(), x.max())
    ax.set_ylim(y.min(), y.max())
    if panel["plane"] == "ab":
        ax.set_aspect("equal")
        ax.plot([x.min(), x.max()], [-x.min(), -x.max()], ":", color="0.5", lw=0.8)  # a = -b
    fs = 8 if small else 10
    ax.set_xlabel(AXIS_LABEL[h], fontsize=fs)
    ax.set_ylabel(AXIS_LABEL[v], fontsize=fs)
    ax.tick_params(labelsize=fs - 1)
    counts = f"{panel['coarse_pd']}/{panel['coarse_points']} PD"
    if small:
        ax.set_title(f"3.1{pid}: {fixed} = {panel['fixed']:g} MPa ({counts})", fontsize=fs + 1)
    else:
        ax.set_title(f"Fig. 3.1{pid}: {panel['title']}, σ_pl = {meta['slice_sigma']:g} MPa "
                     f"({counts})", fontsize=fs + 1)
    return mesh


def legend_text(meta):
    dyn = "" if meta["mass_scale"] == 0 else f", ρh²/Δt² = {meta['mass_scale']:.4g} MPa"
    return (f"A = C + T [MPa], layout {meta['layout']}, τ33 {meta['tau33']}, "
            f"E = {meta['E']:g}, ν = {meta['nu']:g}, E_T = {meta['E_T']:.6g}, "
            f"σ_pl = {meta['slice_sigma']:g} MPa{dyn}.  colour: λ_min/2G;  black: λ_min = 0;  "
            f"+/−: PD / not PD on the grid;  red: yield f = 0;  orange dashed: thesis √I2 = σ_pl")


def plot(out_dir):
    with open(os.path.join(out_dir, "monotonicity.json")) as f:
        meta = json.load(f)
    slices = read_array(os.path.join(out_dir, "monotonicity_slices.csv"), n_text=2)
    written = []
    for panel in meta["panels"]:
        fig, ax = plt.subplots(figsize=(7.2, 6.4) if panel["plane"] == "ab" else (8.5, 4.6))
        mesh = draw_panel(ax, meta, panel, slices)
        fig.colorbar(mesh, ax=ax, label="λ_min(A) / 2G (clipped)")
        fig.text(0.01, 0.005, legend_text(meta), fontsize=6, wrap=True)
        fig.tight_layout(rect=(0, 0.04, 1, 1))
        path = os.path.join(out_dir, f"fig3_1_{panel['id']}.png")
        fig.savefig(path, dpi=120)
        plt.close(fig)
        written.append(path)

    fig, axes = plt.subplots(3, 4, figsize=(19, 13))
    for ax, panel in zip(axes.flat, meta["panels"]):
        mesh = draw_panel(ax, meta, panel, slices, small=True)
    fig.colorbar(mesh, ax=axes, shrink=0.6, label="λ_min(A) / 2G (clipped)")
    fig.suptitle(legend_text(meta), fontsize=9)
    path = os.path.join(out_dir, "fig3_1_overview.png")
    fig.savefig(path, dpi=90)
    plt.close(fig)
    written.append(path)

    # Panel a (c = 0) for every sigma_pl layer: the PD region grows with sigma_pl (an ellipse
    # per layer, thesis: "for successive layers in sigma the PD region is an ellipsoid").
    grid = read_array(os.path.join(out_dir, "monotonicity_grid.csv"))
    c0 = grid[np.isclose(grid["c"], 0.0)]
    if len(c0):
        sigmas = np.unique(c0["sigma_pl"])
        fig, ax = plt.subplots(figsize=(7.5, 6.5))
        cmap = plt.get_cmap("viridis")
        for i, s in enumerate(sigmas):
            layer = c0[c0["sigma_pl"] == s]
            a_vals = np.unique(layer["a"])
            b_vals = np.unique(layer["b"])
            lam = layer["lambda_min"].reshape(len(a_vals), len(b_vals))
            if lam.min() < 0 < lam.max():
                aa, bb = np.meshgrid(a_vals, b_vals, indexing="ij")
                ax.contour(aa, bb, lam, levels=[0.0], colors=[cmap(i / max(len(sigmas) - 1, 1))],
                           linewidths=1.0)
        sm = plt.cm.ScalarMappable(cmap=cmap,
                                   norm=plt.Normalize(vmin=sigmas.min(), vmax=sigmas.max()))
        fig.colorbar(sm, ax=ax, label="σ_pl [MPa]")
        ax.set_aspect("equal")
        ax.set_xlabel(AXIS_LABEL["a"])
        ax.set_ylabel(AXIS_LABEL["b"])
        ax.set_title("PD boundary λ_min(A) = 0 in the (a,b) plane, c = 0, per σ_pl layer\n"
                     f"(4-D grid, layout {meta['layout']}, τ33 {meta['tau33']})", fontsize=10)
        fig.tight_layout()
        path = os.path.join(out_dir, "fig3_1_sigma_layers.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written


def main(argv=None):
    ap = parser("plot-monotonicity", __doc__)
    ap.add_argument("out_dir")
    args = ap.parse_args(argv)
    written = plot(args.out_dir)
    print(f"plot_monotonicity: wrote {len(written)} PNG files to {args.out_dir}")
