#!/usr/bin/python3
"""Thesis Table 5.1: relative difference (LARGE - INFINI)/LARGE at the node in the middle of the
contact at step 6, from two roller runs of problems/z2_large.toml and problems/z2_infini.toml.

usage: /usr/bin/python3 scripts/z2_table.py OUT_LARGE OUT_INFINI [--node 26] [--step 6]
The node is the thesis's number (1-based). Values are the nodal averages written to the VTU files.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_scene import read_vtu  # noqa: E402

THESIS = {"eps_xx": -3.2, "eps_yy": -0.86, "eps_xy": -22.0, "tau_xx": 3.72, "tau_yy": -11.3,
          "tau_xy": 4.5, "u_x": 16.0, "u_y": 0.15}


def values(out, node, step):
    _, _, pd, _ = read_vtu(os.path.join(out, "step_%04d.vtu" % step))
    i = node - 1
    s, e, u = pd["stress_nodal"][i], pd["strain_nodal"][i], pd["displacement"][i]
    return {"eps_xx": e[0], "eps_yy": e[1], "eps_xy": e[3], "tau_xx": s[0], "tau_yy": s[1],
            "tau_xy": s[3], "u_x": u[0], "u_y": u[1]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("large")
    ap.add_argument("infini")
    ap.add_argument("--node", type=int, default=26)
    ap.add_argument("--step", type=int, default=6)
    a = ap.parse_args()
    large, infini = values(a.large, a.node, a.step), values(a.infini, a.node, a.step)
    print("| quantity | LARGE | INFINI | (LARGE−INFINI)/LARGE [%] | thesis Table 5.1 [%] |")
    print("|---|---:|---:|---:|---:|")
    for k in THESIS:
        rel = 100.0 * (large[k] - infini[k]) / large[k] if large[k] != 0 else float("nan")
        print("| %s | %.4g | %.4g | %.3g | %.3g |" % (k, large[k], infini[k], rel, THESIS[k]))


if __name__ == "__main__":
    main()
