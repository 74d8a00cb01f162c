"""The Cattaneo-Mindlin protocol under prescribed forces against Cattaneo's stick zone
(docs/validation.md, "Cattaneo-Mindlin under prescribed forces").

usage: ./rollerpy cattaneo-mindlin [--out out/cattaneo_mindlin] [--refine 1,2,3]
                                  [--backends ipopt,penalty] [--roller build/roller]

Runs problems/cattaneo_mindlin.toml (P = 10000 N/mm pressed frictionlessly, then Q = mu P / 2 with
mu = 0.15, P held, rotation blocked) and measures from the last step of contact.csv the half-widths
by moments of nodal forces, which are exact for the ellipses of the theory and do not depend on
the node spacing of the graded mesh: the pressure ~ sqrt(1 - x^2/a^2) has standard deviation a/2,
and so has the traction deficit mu p - |q| ~ sqrt(1 - x^2/c^2) (zero in the slip zone) with c/2.
Nodal forces are pressures times tributary lengths (the midpoint rule on the contact nodes).
Compares a with Hertz's sqrt(4PR/(pi E*)) and c/a with Cattaneo's sqrt(1 - Q/(mu P)); prints a
Markdown table with the centre's horizontal offset (the tangential compliance) and the run time.
"""
import math
import os
import sys

import numpy as np

from ..command import parser
from ..outputs import contact_profile, read_rows, read_summary
from ..paths import DEFAULT_ROLLER, PROBLEMS
from ..runner import RunFailed, contact_option, roller_command, run

MU, E, NU, R = 0.15, 2.1e5, 0.49, 100.0


def half_widths(contact_rows, step):
    profile = contact_profile(contact_rows, step)
    x, p, t = profile.x, profile.p_n, profile.p_t
    mid = 0.5 * (x[1:] + x[:-1])
    length = np.empty_like(x)
    length[1:-1] = mid[1:] - mid[:-1]
    length[0], length[-1] = mid[0] - x[0], x[-1] - mid[-1]
    on = p > 1e-3 * p.max()

    def width(w):
        xm = (w * x).sum() / w.sum()
        return 2.0 * math.sqrt((w * (x - xm) ** 2).sum() / w.sum())

    a = width(np.where(on, p, 0.0) * length)
    c = width(np.where(on, np.clip(MU * p - np.abs(t), 0.0, None), 0.0) * length)
    return a, c


def main(argv=None):
    ap = parser("cattaneo-mindlin", __doc__)
    ap.add_argument("--out", default="out/cattaneo_mindlin")
    ap.add_argument("--refine", default="1,2,3")
    ap.add_argument("--backends", default="ipopt,penalty")
    ap.add_argument("--roller", default=DEFAULT_ROLLER)
    args = ap.parse_args(argv)
    e_star = E / (1.0 - NU ** 2)
    rows = []
    for refine in [int(k) for k in args.refine.split(",")]:
        for backend in args.backends.split(","):
            out = os.path.join(args.out, "%s_r%d" % (backend, refine))
            cmd = roller_command(args.roller, os.path.join(PROBLEMS, "cattaneo_mindlin.toml"), out, "--overwrite",
                                 "--refine", refine, *contact_option(backend))
            try:
                run(cmd, out + ".log").check()
            except RunFailed as e:
                sys.exit(str(e))
            roller = read_rows(os.path.join(out, "roller.csv"))[-1]
            summary = read_summary(out)
            fx, fy = float(roller["fx"]), float(roller["fy"])
            a, c = half_widths(read_rows(os.path.join(out, "contact.csv")), int(roller["step"]))
            a_hertz = math.sqrt(4.0 * fy * R / (math.pi * e_star))
            expected = math.sqrt(1.0 - abs(fx) / (MU * fy))
            rows.append((refine, backend, summary["ndof"], fy, fx, a, a_hertz, c / a, expected,
                         float(roller["load_offset_x"]), float(summary["wall_s"])))
            print(rows[-1], flush=True)
    print("\n| refine | backend | dofs | P [N/mm] | Q [N/mm] | a [mm] | Hertz | c/a | Cattaneo | diff "
          "| offset x [mm] | run [s] |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print("| %d | %s | %d | %.2f | %.2f | %.4f | %.4f | %.4f | %.4f | %+.4f | %.5f | %.1f |" % (
            r[0], r[1], r[2], r[3], -r[4], r[5], r[6], r[7], r[8], r[7] - r[8], r[9], r[10]))
