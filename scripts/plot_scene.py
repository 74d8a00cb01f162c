#!/usr/bin/python3
"""Thesis-style figures (PNG) from a roller output folder.

usage: /usr/bin/python3 scripts/plot_scene.py OUT_DIR [--steps 4,7] [--profile-steps 0-12]
                                              [--pressure-steps 13] [--hertz] [--mesh-steps 3,6]

Reads fields.pvd / step_NNNN.vtu, contact.csv, roller.csv and scene.resolved.toml of a run and
writes into OUT_DIR/figures/:
  map_<field>_step<N>.png   contour maps of sqrt(I2) (thesis: the von Mises value, so the plastic
                            zone is bounded by the yield stress), tau_xx, tau_yy, tau_xy, eps_xy, u_y
  profile.png               top-surface profile over the steps, u_y magnified x100
  pressure.png              contact pressure p_n (and p_t) along x at the chosen steps
  mesh_step<N>.png          deformed mesh (true scale and u magnified)
  hertz.png                 (--hertz) the last step's pressure against the Hertz solution
Needs numpy and matplotlib from Debian (python3-numpy, python3-matplotlib).
"""
import argparse
import base64
import csv
import math
import os
import struct
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402

DTYPES = {"Float64": ("d", 8), "Int64": ("q", 8), "UInt8": ("B", 1), "Int32": ("i", 4)}


def decode(array):
    """Decodes one inline base64 DataArray written by roller (UInt64 byte-count header)."""
    raw = base64.b64decode(array.text.strip())
    nbytes = struct.unpack("<Q", raw[:8])[0]
    code, size = DTYPES[array.get("type")]
    values = struct.unpack("<%d%s" % (nbytes // size, code), raw[8:8 + nbytes])
    n = int(array.get("NumberOfComponents", "1"))
    return np.array(values).reshape(-1, n) if n > 1 else np.array(values)


def read_vtu(path):
    root = ET.parse(path).getroot()
    piece = root.find("UnstructuredGrid/Piece")
    points = decode(piece.find("Points/DataArray"))[:, :2]
    cells = {a.get("Name"): decode(a) for a in piece.find("Cells")}
    conn, offsets = cells["connectivity"].astype(int), cells["offsets"].astype(int)
    elements, start = [], 0
    for end in offsets:
        elements.append(conn[start:end])
        start = end
    point_data = {a.get("Name"): decode(a) for a in piece.find("PointData")}
    cell_data = {a.get("Name"): decode(a) for a in piece.find("CellData")}
    return points, elements, point_data, cell_data


def triangles(elements):
    tris = []
    for e in elements:
        tris.append(e[:3])
        if len(e) == 4:
            tris.append([e[0], e[2], e[3]])
    return np.array(tris)


def von_mises(s):  # s: [xx, yy, zz, xy]
    p = (s[:, 0] + s[:, 1] + s[:, 2]) / 3.0
    d = s[:, :3] - p[:, None]
    return np.sqrt(1.5 * (np.sum(d * d, axis=1) + 2.0 * s[:, 3] ** 2))


def vtu_path(out, step):
    return os.path.join(out, "step_%04d.vtu" % step)


def parse_steps(text, last):
    steps = []
    for part in text.split(","):
        if "-" in part:
            a, b = part.split("-")
            steps.extend(range(int(a), int(b) + 1))
        elif part:
            steps.append(int(part))
    return [s for s in steps if 0 <= s <= last]


def available_steps(out):
    return sorted(int(f[5:9]) for f in os.listdir(out) if f.startswith("step_") and f.endswith(".vtu"))


def contour_maps(out, figs, steps):
    fields = [
        ("sqrt_I2", "√I2 (von Mises) [MPa]", lambda pd: von_mises(pd["stress_nodal"])),
        ("tau_xx", "τ_xx [MPa]", lambda pd: pd["stress_nodal"][:, 0]),
        ("tau_yy", "τ_yy [MPa]", lambda pd: pd["stress_nodal"][:, 1]),
        ("tau_xy", "τ_xy [MPa]", lambda pd: pd["stress_nodal"][:, 3]),
        ("eps_xy", "ε_xy [-]", lambda pd: pd["strain_nodal"][:, 3]),
        ("u_y", "u_y [mm]", lambda pd: pd["displacement"][:, 1]),
    ]
    for step in steps:
        points, elements, pd, _ = read_vtu(vtu_path(out, step))
        tri = mtri.Triangulation(points[:, 0], points[:, 1], triangles(elements))
        for name, label, get in fields:
            values = get(pd)
            fig, ax = plt.subplots(figsize=(10, 3.2))
            cs = ax.tricontourf(tri, values, levels=20, cmap="viridis")
            ax.tricontour(tri, values, levels=10, colors="k", linewidths=0.3)
            fig.colorbar(cs, ax=ax, label=label)
            ax.set_aspect("equal")
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("y [mm]")
            ax.set_title("%s, step %d" % (label, step))
            fig.tight_layout()
            fig.savefig(os.path.join(figs, "map_%s_step%d.png" % (name, step)), dpi=110)
            plt.close(fig)


def top_nodes(points):
    top = np.where(np.abs(points[:, 1] - points[:, 1].max()) < 1e-9 * (1 + points[:, 1].max()))[0]
    return top


def profile(out, figs, steps):
    points0, _, _, _ = read_vtu(vtu_path(out, 0))
    top = top_nodes(points0)
    order = top[np.argsort(points0[top, 0])]
    fig, ax = plt.subplots(figsize=(10, 4))
    for step in steps:
        _, _, pd, _ = read_vtu(vtu_path(out, step))
        u = pd["displacement"]
        ax.plot(points0[order, 0] + u[order, 0], 100.0 * u[order, 1], label="step %d" % step, lw=1)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("u_y × 100 [mm]")
    ax.set_title("top surface profile (u_y magnified ×100)")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "profile.png"), dpi=110)
    plt.close(fig)


def read_contact(out):
    rows = list(csv.DictReader(open(os.path.join(out, "contact.csv"))))
    return rows


def pressure(out, figs, steps):
    rows = read_contact(out)
    fig, ax = plt.subplots(figsize=(8, 4))
    for step in steps:
        r = sorted((row for row in rows if int(row["step"]) == step), key=lambda row: float(row["x"]))
        if not r:
            continue
        x = [float(row["x"]) for row in r]
        ax.plot(x, [float(row["p_n"]) for row in r], "o-", ms=3, label="p_n, step %d" % step)
        ax.plot(x, [float(row["p_t"]) for row in r], "s--", ms=2, label="p_t, step %d" % step)
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("contact pressure [MPa]")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(figs, "pressure.png"), dpi=110)
    plt.close(fig)


def deformed_mesh(out, figs, steps):
    points0, elements, _, _ = read_vtu(vtu_path(out, 0))
    for step in steps:
        _, _, pd, _ = read_vtu(vtu_path(out, step))
        u = pd["displacement"][:, :2]
        fig, axes = plt.subplots(1, 2, figsize=(12, 4))
        for ax, scale in zip(axes, (1.0, 10.0)):
            x = points0 + scale * u
            for e in elements:
                loop = list(e) + [e[0]]
                ax.plot(points0[loop, 0], points0[loop, 1], color="0.8", lw=0.5)
                ax.plot(x[loop, 0], x[loop, 1], color="k", lw=0.7)
            ax.set_aspect("equal")
            ax.set_title("step %d, displacement ×%g (grey: initial)" % (step, scale))
        fig.tight_layout()
        fig.savefig(os.path.join(figs, "mesh_step%d.png" % step), dpi=110)
        plt.close(fig)


def hertz(out, figs):
    import tomllib  # Python 3.11
    scene = tomllib.load(open(os.path.join(out, "scene.resolved.toml"), "rb"))
    rows = read_contact(out)
    last = max(int(r["step"]) for r in rows)
    roller = list(csv.DictReader(open(os.path.join(out, "roller.csv"))))[-1]
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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--steps", default="", help="steps for the contour maps, e.g. 4,7 (default: the last)")
    ap.add_argument("--profile-steps", default="", help="steps for the surface profile, e.g. 0-12 (default: all)")
    ap.add_argument("--pressure-steps", default="", help="steps for the pressure plot (default: the last)")
    ap.add_argument("--mesh-steps", default="", help="steps for deformed-mesh plots, e.g. 3,6")
    ap.add_argument("--hertz", action="store_true", help="also plot the pressure against Hertz")
    args = ap.parse_args()
    steps = available_steps(args.out)
    if not steps:
        sys.exit("plot_scene: no step_NNNN.vtu in %s (was the run made with output.vtu = true?)" % args.out)
    last = steps[-1]
    figs = os.path.join(args.out, "figures")
    os.makedirs(figs, exist_ok=True)
    contour_maps(args.out, figs, parse_steps(args.steps, last) or [last])
    profile(args.out, figs, parse_steps(args.profile_steps, last) or steps)
    if os.path.exists(os.path.join(args.out, "contact.csv")):
        pressure(args.out, figs, parse_steps(args.pressure_steps, last) or [last])
    if args.mesh_steps:
        deformed_mesh(args.out, figs, parse_steps(args.mesh_steps, last))
    if args.hertz:
        hertz(args.out, figs)
    print("plot_scene: figures in %s" % figs)


if __name__ == "__main__":
    main()
