"""The shakedown map of `roller shakedown-limit SCENE --map FOLDER` (docs/model.md, Melan's bound):
FOLDER/shakedown_limit_map.csv drawn as FOLDER/shakedown_limit_map.png, the scene's Melan bound
(elastic, and kinematic when the strip hardens kinematically) over the traction q/p beside the
half-plane's limits from McEwen's stresses (rollerpy.line_contact_shakedown): Johnson's elastic
shakedown limit (in-plane: subsurface, and 1/mu at the surface), the surface limit of a von Mises
strip with the strip's nu, and the alternating plasticity limit of linear kinematic hardening.

usage: ./rollerpy plot-melan-map FOLDER"""
import os
import sys

import numpy as np

from ..command import parser
from ..line_contact_shakedown import kinematic_shakedown_limit, shakedown_limit, von_mises_surface_limit
from ..outputs import num, read_rows
from ..runner import save_figure
from . import plt

CSV, PNG = "shakedown_limit_map.csv", "shakedown_limit_map.png"


def main(argv=None):
    ap = parser("plot-melan-map", __doc__)
    ap.add_argument("folder")
    args = ap.parse_args(argv)
    rows = read_rows(os.path.join(args.folder, CSV)) if os.path.exists(os.path.join(args.folder, CSV)) else []
    if not rows:
        print("plot-melan-map: %s has no %s (roller shakedown-limit SCENE --map FOLDER writes it)" % (
            args.folder, CSV), file=sys.stderr)
        return 2
    q = np.array([num(r["q_over_p"]) for r in rows])
    nu = num(rows[0]["nu"])
    mus = np.linspace(0.0, 0.5, 11)
    fig, ax = plt.subplots(figsize=(8.5, 5.5))
    johnson = [shakedown_limit(m) for m in mus]
    ax.plot(mus, johnson, "k-", lw=1.2, label="Johnson: elastic shakedown (in-plane)")
    ax.plot(mus[1:], 1.0 / mus[1:], "k:", lw=1.0, label="surface, in-plane: 1/μ")
    surface = [von_mises_surface_limit(m, nu, x=np.linspace(-4.0, 4.0, 801), tol=5e-3) for m in mus[1:]]
    ax.plot(mus[1:], surface, "-.", color="0.4", lw=1.0, label="surface, von Mises with ν = %.2g" % nu)
    elastic = np.array([num(r["elastic_p0_over_k"]) for r in rows])
    ax.plot(q, elastic, "o", color="tab:blue", ms=6, label="roller shakedown-limit: elastic")
    if any(r["kinematic_p0_over_k"] for r in rows):
        ax.plot(mus, [kinematic_shakedown_limit(m, depths=np.linspace(0.0, 1.5, 61), x=np.linspace(-6, 6, 481))
                      for m in mus], "--", color="tab:red", lw=1.0,
                label="alternating plasticity (kinematic, in-plane)")
        kinematic = np.array([num(r["kinematic_p0_over_k"]) for r in rows])
        ax.plot(q, kinematic, "s", color="tab:red", ms=5, mfc="none", label="roller shakedown-limit: kinematic")
    ax.set_xlabel("traction coefficient q/p")
    ax.set_ylabel("load p0/k at the limit")
    ax.set_xlim(0.0, 0.52)
    ax.set_ylim(0.0, 6.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title("Shakedown map of %s (%s)" % (os.path.basename(os.path.abspath(args.folder)), CSV), fontsize=10)
    fig.tight_layout()
    path = os.path.join(args.folder, PNG)
    save_figure(fig, path, dpi=120)
    plt.close(fig)
    print("plot-melan-map: %s" % path)
    return 0
