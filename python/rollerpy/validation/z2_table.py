"""Thesis Table 5.1: relative difference (LARGE - INFINI)/LARGE at a node at step 6, from two
roller runs of problems/z2_large.toml and problems/z2_infini.toml, for the totals and for the
increments of step 6 side by side (the thesis does not say which it compares; its strains are the
updated-Lagrangian strain of one step, its §2.1.3).

usage: ./rollerpy z2-table OUT_LARGE OUT_INFINI [--node 26] [--step 6]
The node is the thesis's number (1-based; 26: x = 50 mm on the top, under the roller's centre at
step 6, the trailing edge of the contact; 21: x = 40, its middle). Values are the nodal averages
written to the VTU files; the increment of the strain is the VTU's strain_increment (the strain
of the step's own displacement), of the stress and displacement the difference to step - 1.
"""
import sys

from ..command import parser
from ..vtu import read_vtu, vtu_path

THESIS = {"eps_xx": -3.2, "eps_yy": -0.86, "eps_xy": -22.0, "tau_xx": 3.72, "tau_yy": -11.3,
          "tau_xy": 4.5, "u_x": 16.0, "u_y": 0.15}


def values(out, node, step):
    """(totals, increments of the step) at the node."""
    pd = read_vtu(vtu_path(out, step)).point_data
    before = read_vtu(vtu_path(out, step - 1)).point_data
    i = node - 1
    s, e, u = pd["stress_nodal"][i], pd["strain_nodal"][i], pd["displacement"][i]
    ds, de, du = s - before["stress_nodal"][i], pd["strain_increment_nodal"][i], u - before["displacement"][i]
    total = {"eps_xx": e[0], "eps_yy": e[1], "eps_xy": e[3], "tau_xx": s[0], "tau_yy": s[1], "tau_xy": s[3],
             "u_x": u[0], "u_y": u[1]}
    step_only = {"eps_xx": de[0], "eps_yy": de[1], "eps_xy": de[3], "tau_xx": ds[0], "tau_yy": ds[1],
                 "tau_xy": ds[3], "u_x": du[0], "u_y": du[1]}
    return total, step_only


def relative(large, infini):
    return 100.0 * (large - infini) / large if large != 0 else float("nan")


def main(argv=None):
    ap = parser("z2-table", __doc__)
    ap.add_argument("large")
    ap.add_argument("infini")
    ap.add_argument("--node", type=int, default=26)
    ap.add_argument("--step", type=int, default=6)
    a = ap.parse_args(argv)
    if a.step < 1:
        sys.exit("z2_table: --step %d: expected a step >= 1 (the increment needs the step before)" % a.step)
    (lt, li), (it, ii) = values(a.large, a.node, a.step), values(a.infini, a.node, a.step)
    print("node %d, step %d: totals and the step's increments; (LARGE-INFINI)/LARGE [%%]" % (a.node, a.step))
    print("| quantity | LARGE total | INFINI total | total [%] | LARGE step | INFINI step | step [%] "
          "| thesis Table 5.1 [%] |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for k in THESIS:
        print("| %s | %.4g | %.4g | %.3g | %.4g | %.4g | %.3g | %.3g |" % (
            k, lt[k], it[k], relative(lt[k], it[k]), li[k], ii[k], relative(li[k], ii[k]), THESIS[k]))
