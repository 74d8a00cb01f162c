"""Measures the thesis's chapter-5 statements that docs/thesis-figures.md checks against maps
(Z1: figures 5.4-5.6; Z2: 5.10-5.12), from the output folders of the shipped scenes.

usage: ./rollerpy thesis-statements [--out out]
reads OUT/z1_outf10 and OUT/z2_large, OUT/z2_infini (runs of problems/<name>.toml) and prints,
per statement, the numbers the page quotes. Element values (integration-point means) are used
where the thesis says its maps are Gauss-point values (Z1, its figure 5.3); ε is the VTU's
Green-Lagrange total `strain` and the step's own `strain_increment`, component order xx, yy, zz, xy.
"""
import os

import matplotlib.tri as mtri
import numpy as np

from ..command import parser
from ..outputs import read_contact, touching_x
from ..plots import plt
from ..plots.fields import von_mises
from ..vtu import read_vtu, reference_mesh, top_nodes, triangles, vtu_path


def contact_nodes(out, step):
    """x of the nodes in contact at the step (contact.csv), sorted."""
    return touching_x(read_contact(out), step)


def top_layer(out, step):
    """The elements touching the top surface, with their current centroid x, sorted by x, and the
    step's element data."""
    vtu = read_vtu(vtu_path(out, step))  # points: the deformed positions
    points, elements, cd = vtu.points, vtu.elements, vtu.cell_data
    top = set(top_nodes(reference_mesh(out)[0]))
    x = points[:, 0]
    layer = [i for i, e in enumerate(elements) if top.intersection(e)]
    centre = {i: float(np.mean(x[elements[i]])) for i in layer}
    return sorted(layer, key=centre.get), centre, cd


def z1_middle_zone(out, step):
    """Figures 5.3 (i), 5.4: τ_xy in the contact's top layer changes sign from compression (left)
    to tension (right) at a middle sub-zone where ε_xy is small."""
    xs = contact_nodes(out, step)
    layer, centre, cd = top_layer(out, step)
    inside = [i for i in layer if xs[0] <= centre[i] <= xs[-1]]
    tau = cd["stress"][inside, 3]
    crossing = [k for k in range(len(inside) - 1) if tau[k] < 0 <= tau[k + 1]]
    print("Z1 step %d: contact x = %.1f..%.1f mm, %d top-layer elements inside" % (step, xs[0], xs[-1], len(inside)))
    print("  tau_xy left to right [MPa]: " + " ".join("%.0f" % t for t in tau))
    for name in ("strain", "strain_increment"):
        e = np.abs(cd[name][inside, 3])
        if crossing:
            k = crossing[0]
            middle = max(e[k], e[k + 1])
            print("  |%s_xy| at the tau_xy sign change (x = %.1f..%.1f): %.2e; largest in the contact %.2e (ratio %.2f)"
                  % (name, centre[inside[k]], centre[inside[k + 1]], middle, e.max(), middle / e.max()))
    if not crossing:
        print("  no sign change of tau_xy from - to + inside the contact")


def z1_uy_ellipse(out, step):
    """Figure 5.5: the u_y contours under the roller are near-elliptic. The contour at half the
    surface's largest depression, fitted by a half-ellipse centred on the top surface."""
    vtu = read_vtu(vtu_path(out, step))
    current, elements, u = vtu.points, vtu.elements, vtu.point_data["displacement"]
    points = reference_mesh(out)[0]
    top = top_nodes(points)
    level = 0.5 * u[top, 1].min()
    tri = mtri.Triangulation(current[:, 0], current[:, 1], triangles(elements))
    fig, ax = plt.subplots()
    cs = ax.tricontour(tri, u[:, 1], levels=[level])
    plt.close(fig)
    paths = [seg for seg in cs.allsegs[0] if len(seg) > 2]
    seg = max(paths, key=len)
    ytop = points[:, 1].max()
    x, depth = seg[:, 0], ytop - seg[:, 1]
    xc, a, b = 0.5 * (x.min() + x.max()), 0.5 * (x.max() - x.min()), depth.max()
    ellipse = b * np.sqrt(np.clip(1.0 - ((x - xc) / a) ** 2, 0.0, None))
    rms = float(np.sqrt(np.mean((depth - ellipse) ** 2)))
    reaches_bottom = seg[:, 1].min() <= points[:, 1].min() + 1e-6
    print("Z1 step %d: u_y contour at %.3f mm: %d points, x = %.1f..%.1f, depth %.1f of %.1f mm%s; "
          "half-ellipse fit: RMS deviation %.2f mm = %.0f %% of the depth"
          % (step, level, len(seg), x.min(), x.max(), b, ytop - points[:, 1].min(),
             " (reaches the bottom)" if reaches_bottom else "", rms, 100.0 * rms / b))


def z1_fold(out, steps):
    """Figure 5.6: a fold (a raised bump of the top surface) forms behind the roller at step 4,
    when it moves up and to the left, and grows when it is pressed in again at step 5."""
    top = top_nodes(reference_mesh(out)[0])
    for step in steps:
        vtu = read_vtu(vtu_path(out, step))
        xs = contact_nodes(out, step)
        x = vtu.points[top, 0]
        uy = vtu.point_data["displacement"][top, 1]
        groove = np.argmin(uy)
        highest = np.argmax(uy)
        line = "Z1 step %d: groove bottom u_y = %+.3f mm at x = %.1f; highest top node u_y = %+.3f at x = %.1f" % (
            step, uy[groove], x[groove], uy[highest], x[highest])
        if xs:
            behind = (x > xs[-1]) & (x < xs[-1] + 30.0)  # the roller moves toward -x: behind is +x
            k = np.argmax(np.where(behind, uy, -np.inf))
            line += "; contact x = %.1f..%.1f, highest within 30 mm behind it u_y = %+.3f at x = %.1f" % (
                xs[0], xs[-1], uy[k], x[k])
        print(line)


def z2_large_vs_infini(large, infini, step):
    """Figures 5.10-5.12: LARGE and INFINI "similar qualitatively, slightly different
    quantitatively": per field, ||L - I|| / ||L|| over the elements and the correlation of L and I."""
    cl = read_vtu(vtu_path(large, step)).cell_data
    ci = read_vtu(vtu_path(infini, step)).cell_data
    fields = {"sqrt_I2 (von Mises)": (von_mises(cl["stress"]), von_mises(ci["stress"]))}
    for k, c in (("xx", 0), ("yy", 1), ("xy", 3)):
        fields["tau_" + k] = (cl["stress"][:, c], ci["stress"][:, c])
    for k, c in (("xx", 0), ("yy", 1), ("xy", 3)):
        fields["eps_" + k] = (cl["strain"][:, c], ci["strain"][:, c])
        fields["deps_" + k] = (cl["strain_increment"][:, c], ci["strain_increment"][:, c])
    print("Z2 step %d, element values, LARGE against INFINI:" % step)
    for name, (a, b) in fields.items():
        rel = np.linalg.norm(a - b) / np.linalg.norm(a)
        corr = np.corrcoef(a, b)[0, 1]
        print("  %-20s ||L-I||/||L|| = %5.1f %%   correlation %.4f   largest |L| %.3g, |I| %.3g"
              % (name, 100.0 * rel, corr, np.abs(a).max(), np.abs(b).max()))


def main(argv=None):
    ap = parser("thesis-statements", __doc__)
    ap.add_argument("--out", default="out", help="the folder holding the scenes' output folders")
    args = ap.parse_args(argv)
    z1 = os.path.join(args.out, "z1_outf10")
    for step in (4, 7):
        z1_middle_zone(z1, step)
    for step in (4, 7):
        z1_uy_ellipse(z1, step)
    z1_fold(z1, (3, 4, 5, 6))
    z2_large_vs_infini(os.path.join(args.out, "z2_large"), os.path.join(args.out, "z2_infini"), 6)
