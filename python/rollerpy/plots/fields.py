"""The fields the figures draw, under the names of the VTU files (docs/scenes.md, Outputs): one
name per quantity, with its unit, whether it is signed (a diverging colour map centred at zero)
or a magnitude (a sequential one), and how to get its nodal and element values from a step's VTU;
the contour levels and colours shared by maps, overlays and comparisons (docs/figures.md)."""
import math
from dataclasses import dataclass

import numpy as np
from matplotlib.colors import Normalize
from matplotlib.ticker import MaxNLocator


def von_mises(s):  # s: [xx, yy, zz, xy]
    p = (s[:, 0] + s[:, 1] + s[:, 2]) / 3.0
    d = s[:, :3] - p[:, None]
    return np.sqrt(1.5 * (np.sum(d * d, axis=1) + 2.0 * s[:, 3] ** 2))


def nodal_mean(vtu, cell_values):
    """The mean of the elements around each node: the VTU has no nodal array for every field."""
    counts = np.array([len(e) for e in vtu.elements])
    nodes = np.concatenate([np.asarray(e) for e in vtu.elements])
    total = np.zeros(len(vtu.points))
    seen = np.zeros(len(vtu.points))
    np.add.at(total, nodes, np.repeat(cell_values, counts))
    np.add.at(seen, nodes, 1.0)
    return total / np.maximum(seen, 1.0)


@dataclass(frozen=True)
class Field:
    unit: str         # shown in brackets on colour bars, axes and legend titles
    signed: bool      # signed: diverging map centred at 0; else a magnitude: sequential map
    nodal: object     # Vtu -> nodal values
    element: object   # Vtu -> element values, or None (a nodal quantity)
    meaning: str = ""  # said once in the title

    def label(self, name):
        return "%s [%s]" % (name, self.unit)


def _tensor(nodal_array, cell_array, column, unit, meaning):
    return Field(unit, True, lambda v: v.point_data[nodal_array][:, column],
                 lambda v: v.cell_data[cell_array][:, column], meaning)


COMPONENTS = {"xx": 0, "yy": 1, "zz": 2, "xy": 3}
FIELDS = {}
for _c, _k in COMPONENTS.items():
    FIELDS["stress_" + _c] = _tensor("stress_nodal", "stress", _k, "MPa", "Cauchy stress")
for _c, _k in COMPONENTS.items():
    FIELDS["strain_" + _c] = _tensor("strain_nodal", "strain", _k, "-", "total Green-Lagrange strain")
for _c, _k in COMPONENTS.items():
    FIELDS["strain_increment_" + _c] = _tensor("strain_increment_nodal", "strain_increment", _k, "-",
                                               "strain of the step's increment")
FIELDS.update({
    "sqrt_I2": Field("MPa", False, lambda v: v.point_data["sqrt_I2_nodal"], lambda v: v.cell_data["sqrt_I2"],
                     "√(½ s:s)"),
    "von_mises": Field("MPa", False, lambda v: von_mises(v.point_data["stress_nodal"]),
                       lambda v: v.cell_data["von_mises"], "√(3/2 s:s), the thesis's √I2"),
    "eq_plastic_strain": Field("-", False, lambda v: nodal_mean(v, v.cell_data["eq_plastic_strain"]),
                               lambda v: v.cell_data["eq_plastic_strain"], "equivalent plastic strain"),
    "displacement_x": Field("mm", True, lambda v: v.point_data["displacement"][:, 0], None),
    "displacement_y": Field("mm", True, lambda v: v.point_data["displacement"][:, 1], None),
})
MAP_FIELDS = [n for n in FIELDS if not n.endswith("_zz")]  # the maps drawn without --fields
STRESSES = ["von_mises", "stress_xx", "stress_yy", "stress_xy"]  # overlays, comparisons
# The names of earlier versions, for the message that refuses them.
RENAMED = {"tau_" + c: "stress_" + c for c in COMPONENTS}
RENAMED.update({"eps_" + c: "strain_" + c for c in COMPONENTS})
RENAMED.update({"deps_" + c: "strain_increment_" + c for c in COMPONENTS})
RENAMED.update({"u_x": "displacement_x", "u_y": "displacement_y"})


def unknown_field(name):
    """Why `name` is not a field, or None when it is one."""
    if name in FIELDS:
        return None
    hint = " (now %s, the VTU's name)" % RENAMED[name] if name in RENAMED else ""
    return "%s: unknown field%s; fields: %s" % (name, hint, ", ".join(FIELDS))


def contour_levels(values, levels):
    """Explicit levels: a list of values, or a spacing (one number) turned into the multiples of
    it inside the data's range; None: about ten round values."""
    lo, hi = float(np.min(values)), float(np.max(values))
    if levels is None:
        return [v for v in MaxNLocator(nbins=10).tick_values(lo, hi) if lo < v < hi]
    if len(levels) == 1:
        step = levels[0]
        return [k * step for k in range(math.floor(lo / step), math.ceil(hi / step) + 1) if lo < k * step < hi]
    return [v for v in levels if lo < v < hi]


def colours(field, values):
    """The colour map and its normalisation: signed fields diverging (RdBu_r) with limits
    symmetric about zero, so that white is zero on every map; magnitudes sequential from zero."""
    lo, hi = float(np.min(values)), float(np.max(values))
    if field.signed:
        m = max(abs(lo), abs(hi)) or 1.0
        return "RdBu_r", Normalize(-m, m)
    return "viridis", Normalize(min(lo, 0.0), hi if hi > min(lo, 0.0) else min(lo, 0.0) + 1.0)


def label_lines(ax, cs):
    """Contour labels that leave the lines readable: inline with a gap as wide as a character,
    a true minus sign (a hyphen merges with the line it sits on), one level in two when there are
    more than six (neighbouring labels of close lines overlap); the zero line unlabelled (on signed
    maps the colours say where it is, and near a free surface it wanders through values close to
    zero)."""
    shown = cs.levels if len(cs.levels) <= 6 else cs.levels[1::2]
    shown = [v for v in shown if v != 0.0]
    if shown:
        ax.clabel(cs, shown, inline=True, fmt=number_text, fontsize=8, inline_spacing=4)


def number_text(value, _=None):
    """%g with a true minus sign: labels and colour-bar ticks."""
    return ("%g" % value).replace("-", "\u2212")
