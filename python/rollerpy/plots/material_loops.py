"""A scene's [material] at a point in uniaxial stress, the check of a calibrated hardening law
before it rolls (docs/validation.md, Hardening laws: the rail steel): strain-controlled loops at a
few amplitudes beside the law's monotonic closed form, and the ratchet strain per cycle under an
asymmetric stress cycle. Writes FOLDER/material_loops.csv and FOLDER/material_loops.png.

usage: ./rollerpy material-loops SCENE --out FOLDER [--amplitudes 0.0025,0.005,0.01]
       [--cycles 10] [--stress-cycle MAX,MIN]   (stresses in MPa; default 1.72 and -1.09 sigma_y0)"""
import csv
import math
import os
import sys
import tomllib

import numpy as np

from ..command import parser
from ..runner import atomic_file, save_figure
from . import plt

CSV, PNG = "material_loops.csv", "material_loops.png"
STEPS_PER_BRANCH = 100


def monotonic_stress(material, eps_p):
    """sigma(eps_p) of the law's monotonic uniaxial curve: sigma_y0, Voce's term (either sign) and
    the kinematic part (docs/model.md, Hardening laws)."""
    s = material["yield_stress"] - material.get("voce_Q", 0.0) * np.expm1(-material.get("voce_b", 0.0) * eps_p)
    if material.get("hardening", "isotropic") == "chaboche":
        for c, g in zip(material["chaboche_C"], material["chaboche_gamma"]):
            s = s + (c / g * -np.expm1(-g * eps_p) if g > 0.0 else c * eps_p)
    else:  # isotropic, kinematic, mixed: H' eps_p in uniaxial monotonic tension
        e, et = material["E"], material.get("tangent_modulus", 0.0)
        s = s + e * et / (e - et) * eps_p
    return s


def floats(text, name, count=None):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if not values or (count and len(values) != count) or not all(math.isfinite(v) for v in values):
        raise SystemExit("material-loops: %s = %r: expected %s comma-separated numbers" % (
            name, text, count or "one or more"))
    return values


def main(argv=None):
    ap = parser("material-loops", __doc__)
    ap.add_argument("scene")
    ap.add_argument("--out", required=True, help="folder for material_loops.csv and .png")
    ap.add_argument("--amplitudes", default="0.0025,0.005,0.01", help="axial strain amplitudes of the loops")
    ap.add_argument("--cycles", type=int, default=10)
    ap.add_argument("--stress-cycle", default=None, help="MAX,MIN axial stress [MPa] of the ratchet cycle")
    args = ap.parse_args(argv)
    from .. import inprocess  # the native module, only when the command runs
    amplitudes = floats(args.amplitudes, "--amplitudes")
    if args.cycles < 1:
        raise SystemExit("material-loops: --cycles = %d: expected at least 1" % args.cycles)
    scene = inprocess.load_scene(args.scene)
    material = tomllib.loads(scene.toml())["material"]
    if "yield_stress" not in material:
        print("material-loops: %s: [material] has no yield_stress: an elastic material has no loops" % args.scene,
              file=sys.stderr)
        return 2
    sy = material["yield_stress"]
    s_max, s_min = (floats(args.stress_cycle, "--stress-cycle", 2) if args.stress_cycle
                    else [round(1.72 * sy, -1), round(-1.09 * sy, -1)])
    rows = []
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5))
    last_peak = []
    for a in amplitudes:
        path = inprocess._roller.uniaxial_path(scene, "strain", [a, -a] * args.cycles + [a], STEPS_PER_BRANCH)
        last = slice(len(path["strain"]) - 2 * STEPS_PER_BRANCH - 1, None)
        label = "±%.3g %% strain: cycle %d, peak %.0f MPa" % (a * 100, args.cycles, path["stress"][-1])
        line, = ax.plot(path["strain"][last] * 100, path["stress"][last], lw=1.6, label=label)
        ax.plot(path["strain"] * 100, path["stress"], lw=0.6, alpha=0.4, color=line.get_color())
        last_peak.append((a, path["stress"][-1], path["stress"][STEPS_PER_BRANCH]))
        rows += [("strain", a, e, s, ep) for e, s, ep in zip(path["strain"], path["stress"],
                                                             path["eq_plastic_strain"])]
    eps_p = np.linspace(0.0, max(amplitudes), 400)
    sigma = monotonic_stress(material, eps_p)
    total = eps_p + sigma / material["E"]
    keep = total <= max(amplitudes)
    ax.plot(np.r_[0.0, total[keep]] * 100, np.r_[0.0, sigma[keep]], "k--", lw=1.0,
            label="monotonic closed form")
    ax.set_xlabel("axial strain [%]")
    ax.set_ylabel("axial stress [MPa]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("strain-controlled loops: every cycle (thin), cycle %d (bold)" % args.cycles, fontsize=10)

    ratchet = inprocess._roller.uniaxial_path(scene, "stress", [s_max, s_min] * args.cycles, STEPS_PER_BRANCH)
    peaks = ratchet["strain"][STEPS_PER_BRANCH::2 * STEPS_PER_BRANCH]
    per_cycle = np.diff(peaks)
    rows += [("stress", s_max, e, s, ep) for e, s, ep in zip(ratchet["strain"], ratchet["stress"],
                                                             ratchet["eq_plastic_strain"])]
    bx.semilogy(np.arange(2, len(peaks) + 1), np.abs(per_cycle) * 100, "o-", color="tab:red")
    bx.set_xlabel("cycle")
    bx.set_ylabel("ratchet strain per cycle [%] (at the peaks)")
    bx.grid(alpha=0.3, which="both")
    bx.set_title("stress cycle %+g / %+g MPa" % (s_max, s_min), fontsize=10)
    name = scene.title or os.path.basename(args.scene)
    fig.suptitle(name, fontsize=10)
    fig.tight_layout()
    os.makedirs(args.out, exist_ok=True)
    with atomic_file(os.path.join(args.out, CSV), newline="") as f:
        w = csv.writer(f)
        w.writerow(["control", "amplitude_or_max", "strain", "stress_MPa", "eq_plastic_strain"])
        w.writerows(("%s" % r[0], "%.9g" % r[1], "%.9g" % r[2], "%.9g" % r[3], "%.9g" % r[4]) for r in rows)
    save_figure(fig, os.path.join(args.out, PNG), dpi=120)
    plt.close(fig)
    for a, peak, first in last_peak:
        print("material-loops: ±%.3g %% strain: first peak %.1f MPa, cycle %d's %.1f MPa" % (
            a * 100, first, args.cycles, peak))
    print("material-loops: stress cycle %+g / %+g MPa ratchets %.3g %% in cycle 2, %.3g %% in cycle %d" % (
        s_max, s_min, per_cycle[0] * 100, per_cycle[-1] * 100, args.cycles))
    print("material-loops: %s, %s" % (os.path.join(args.out, PNG), os.path.join(args.out, CSV)))
    return 0
