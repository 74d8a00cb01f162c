"""The rolling-contact-fatigue map of a scene's steel (docs/model.md, Fatigue; docs/validation.md,
Fatigue): over the load p0/k and the traction coefficient mu of a line contact, Johnson's
shakedown regions beside Ekberg, Kabo & Andersson's initiation limits and Dang Van's, with the
scene's own load marked. Writes FOLDER/rcf_map.csv and FOLDER/rcf_map.png.

usage: ./rollerpy rcf-map SCENE --out FOLDER [--mu-max 0.6] [--mu-step 0.05]
       [--point P0_OVER_K,MU] [--set KEY=VALUE ...]   (--set as roller run's: e.g. fatigue.dang_van_a=0.3)

From the half-plane's elastic fields (McEwen's closed forms under a Hertz pressure and q = mu p,
plane strain, the out-of-plane stress nu (sigma_x + sigma_z)), not from the scene's strip:
  - Johnson's map (rollerpy.line_contact_shakedown, Melan's theorem with the in-plane yield
    condition): first yield, the elastic shakedown limit, the plastic shakedown (alternating
    plasticity) limit of kinematic hardening, and the surface limit 1/mu; above the last two the
    strip ratchets.
  - Ekberg's surface index FI_surf = mu - k/p0 > 0 above p0/k = 1/mu, and the subsurface index
    FI_sub = tau_eq,a + a_DV sigma_h,max reaching tau_e; Dang Van's max(tau + a_DV sigma_h) reaching
    tau_w. Both are linear in p0 on the elastic cycle, so each limit is a line p0/k = limit / (k phi(mu))
    with phi the largest value over depth of the unit load's cycle (the run's own criteria, through
    rollerpy._roller.fatigue_of_cycle).
k is [material]'s lowest yield stress over sqrt(3) (a softening Voce term lowers it; a [[layer]] or
yield profile at the surface is not read, where a run takes its surface's), a_DV, tau_w and tau_e
the scene's [fatigue]. The point is the scene's largest roller force on its radius
(Hertz, p0 = sqrt(P E'/(pi R)), E' = E/(1 - nu^2), with an elastic roller the two bodies'
1/E' = 1/E'_strip + 1/E'_roller) and its travel's prescribed traction: q_over_p,
|fx|/fy, or 0 (free rolling, or a creep whose traction only a run finds: --run OUT_DIR marks the
load a run measured, --point the one given).
"""
import csv
import math
import os
import sys
import tomllib

import numpy as np

from ..command import parser
from ..line_contact_shakedown import kinematic_shakedown_limit, mcewen, shakedown_limit
from ..outputs import read_summary
from ..runner import atomic_file, save_figure
from . import plt

CSV, PNG = "rcf_map.csv", "rcf_map.png"
DEPTHS = np.r_[0.0, np.geomspace(0.01, 3.0, 120)]  # z/a: the surface, then down to 3a
X = np.linspace(-6.0, 6.0, 481)                    # x/a of a cycle: the load from far ahead to far behind


def unit_cycles(mu, nu):
    """Per depth, the stress cycle [xx, yy, zz, xy] / p0 of a point as the unit load passes,
    framed by rest (the elastic half-plane holds no residual stress)."""
    rest = np.zeros((1, 4))
    for z in DEPTHS:
        sx, sz, t = mcewen(X, z, mu)
        yield np.vstack([rest, np.column_stack((sx, sz, nu * (sx + sz), t)), rest])


def fatigue_factors(mu, nu, a_dv, fatigue_of_cycle):
    """phi(mu): the largest Dang Van value and FI_sub over depth of the unit load (per p0)."""
    dang_van, fi_sub = 0.0, 0.0
    for cycle in unit_cycles(mu, nu):
        f = fatigue_of_cycle(cycle, a_dv)
        dang_van, fi_sub = max(dang_van, f["dang_van"]), max(fi_sub, f["fi_sub"])
    return dang_van, fi_sub


def first_yield(mu):
    """p0/k at which the in-plane Tresca shear first reaches k anywhere (Johnson's map's k)."""
    x, z = np.meshgrid(np.linspace(-3.0, 3.0, 1201), np.linspace(0.0, 2.0, 401))
    sx, sz, t = mcewen(x, z, mu)
    return 1.0 / float(np.max(np.hypot((sx - sz) / 2.0, t)))


def scene_values(resolved):
    """k, E', nu, the [fatigue] constants and the scene's load point (p0/k, mu) from the resolved scene."""
    material = resolved["material"]
    if "yield_stress" not in material:
        raise SystemExit("rcf-map: [material] has no yield_stress: an elastic strip has no shear yield stress k")
    if "fatigue" not in resolved:
        raise SystemExit("rcf-map: the scene has no [fatigue] section: its a_DV, tau_w and tau_e set the "
                         "initiation limits (docs/scenes.md, [fatigue])")
    nu = material["nu"]
    k = (material["yield_stress"] + min(material.get("voce_Q", 0.0), 0.0)) / math.sqrt(3.0)
    e_prime = material["E"] / (1.0 - nu * nu)
    point = None
    roller = resolved.get("roller")
    if roller and "E" in roller:  # an elastic roller: the two bodies' modulus (docs/model.md, Elastic roller)
        roller_prime = roller["E"] / (1.0 - roller.get("nu", 0.3) ** 2)
        e_prime = 1.0 / (1.0 / e_prime + 1.0 / roller_prime)
    if roller:
        path = roller.get("path", [])
        load = max((abs(s.get("fy", 0.0)) for s in path), default=0.0)
        travel = next((s for s in path if s.get("dx", 0.0) != 0.0 and "fy" in s), None)
        if load > 0.0:
            if travel is None:
                mu = 0.0
            elif "q_over_p" in travel:
                mu = abs(travel["q_over_p"])
            else:
                mu = abs(travel.get("fx", 0.0)) / abs(travel["fy"])
            point = (math.sqrt(load * e_prime / (math.pi * roller["radius"])) / k, mu)
    return k, nu, resolved["fatigue"], point


def region(p0_over_k, mu, row):
    """Johnson's region of the load, and the boundary it lies within 1 % of, if any."""
    bounds = [("elastic", row["first_yield"]), ("elastic shakedown", row["shakedown"]),
              ("plastic shakedown (cyclic plasticity)", min(row["plastic_shakedown"], row["surface"]))]
    name = next((n for n, b in bounds if p0_over_k <= b), "ratchetting")
    near = [b for _, b in bounds if abs(p0_over_k - b) <= 0.01 * b]
    return name + (" (within 1 %% of the boundary at p0/k = %.3g)" % near[0] if near else "")


def rcf_rows(mus, nu, k, fatigue, fatigue_of_cycle):
    rows = []
    for mu in mus:
        dang_van, fi_sub = fatigue_factors(mu, nu, fatigue["dang_van_a"], fatigue_of_cycle)
        rows.append({
            "mu": mu,
            "first_yield": first_yield(mu),
            "shakedown": shakedown_limit(mu, tol=1e-3),
            "plastic_shakedown": kinematic_shakedown_limit(mu, depths=np.linspace(0.0, 2.0, 101),
                                                           x=np.linspace(-6.0, 6.0, 601)),
            "surface": 1.0 / mu if mu > 0.0 else math.inf,
            "fi_sub_limit": fatigue["shear_fatigue_limit"] / (k * fi_sub),
            "dang_van_limit": fatigue["dang_van_limit"] / (k * dang_van),
        })
    return rows


def draw(rows, point, title, path):
    mu = np.array([r["mu"] for r in rows])
    col = {key: np.array([r[key] for r in rows]) for key in rows[0]}
    top = 1.15 * max(float(np.max(col["fi_sub_limit"])), float(np.max(col["dang_van_limit"])),
                     float(np.max(col["plastic_shakedown"])), point[0] if point else 0.0)
    fig, ax = plt.subplots(figsize=(11, 6))
    ratchet = np.minimum(col["plastic_shakedown"], col["surface"])
    ax.fill_between(mu, 0.0, col["first_yield"], color="#d8ecd8", label="elastic")
    ax.fill_between(mu, col["first_yield"], col["shakedown"], color="#e8f3c8", label="elastic shakedown")
    ax.fill_between(mu, col["shakedown"], ratchet, color="#fbe7c0", label="plastic shakedown")
    ax.fill_between(mu, ratchet, top, color="#f6d0c8", label="ratchetting")
    ax.plot(mu, col["shakedown"], "k-", lw=1.2)
    ax.plot(mu, ratchet, "k--", lw=1.0)
    ax.plot(mu[mu > 0], col["surface"][mu > 0], "b:", lw=2.0, label="Ekberg FI_surf = 0 (p0/k = 1/μ)")
    ax.plot(mu, col["fi_sub_limit"], "m-", lw=1.8, label="Ekberg FI_sub = τ_e")
    ax.plot(mu, col["dang_van_limit"], "c-.", lw=1.8, label="Dang Van = τ_w")
    if point:
        ax.plot([point[1]], [point[0]], "k*", ms=14, label="the scene: p0/k = %.2f, μ = %.2f" % point)
    ax.set_xlim(mu[0], mu[-1])
    ax.set_ylim(0.0, top)
    ax.set_xlabel("traction coefficient μ = q/p")
    ax.set_ylabel("load p0/k")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    save_figure(fig, path, dpi=120)
    plt.close(fig)


def interpolated(rows, mu, key):
    return float(np.interp(mu, [r["mu"] for r in rows], [r[key] for r in rows]))


def main(argv=None):
    ap = parser("rcf-map", __doc__)
    ap.add_argument("scene")
    ap.add_argument("--out", required=True, help="folder for rcf_map.csv and rcf_map.png")
    ap.add_argument("--mu-max", type=float, default=0.6)
    ap.add_argument("--mu-step", type=float, default=0.05)
    ap.add_argument("--point", default=None, help="P0_OVER_K,MU to mark instead of the scene's load")
    ap.add_argument("--run", default=None, metavar="OUT_DIR",
                    help="mark the load a run of the scene measured (its summary.json's fatigue block: Hertz's p0 "
                         "of its largest force over k, and its traction coefficient)")
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                    help="a scene key as roller run's --set (a TOML value), e.g. fatigue.dang_van_limit=300.0")
    args = ap.parse_args(argv)
    if not (0.0 < args.mu_step <= args.mu_max <= 2.0):
        raise SystemExit("rcf-map: --mu-step %g, --mu-max %g: expected 0 < step <= max <= 2" % (
            args.mu_step, args.mu_max))
    from .. import inprocess  # the native module, only when the command runs
    overrides = {}
    for item in args.set:
        key, _, value = item.partition("=")
        try:
            overrides[key.strip()] = tomllib.loads("v = " + value)["v"]
        except tomllib.TOMLDecodeError:
            raise SystemExit("rcf-map: --set %r: expected KEY=VALUE with a TOML value (a number, a string in "
                             "double quotes, a list)" % item)
    scene = inprocess.load_scene(args.scene, set=overrides)
    k, nu, fatigue, point = scene_values(tomllib.loads(scene.toml()))
    if args.point:
        try:
            point = tuple(float(v) for v in args.point.split(","))
        except ValueError:
            point = ()
        if len(point) != 2 or not all(math.isfinite(v) and v >= 0.0 for v in point):
            raise SystemExit("rcf-map: --point %r: expected P0_OVER_K,MU, two numbers >= 0" % args.point)
    if args.run:
        measured = read_summary(args.run).get("fatigue") if os.path.exists(os.path.join(args.run, "summary.json")) \
            else None
        if not measured or not measured.get("shear_yield"):
            raise SystemExit("rcf-map: --run %s: no summary.json with a fatigue block (a run with [fatigue] and a "
                             "plastic surface writes it)" % args.run)
        point = (measured["peak_pressure"] / measured["shear_yield"], measured["traction_coefficient"])
    mus = np.round(np.arange(0.0, args.mu_max + 1e-9, args.mu_step), 10)
    rows = rcf_rows(mus, nu, k, fatigue, inprocess._roller.fatigue_of_cycle)
    os.makedirs(args.out, exist_ok=True)
    with atomic_file(os.path.join(args.out, CSV), newline="") as f:
        w = csv.writer(f)
        w.writerow(list(rows[0]))
        w.writerows(["%.6g" % v for v in r.values()] for r in rows)
    title = "%s\nk = %.1f MPa, a_DV = %g, τ_w = %g MPa, τ_e = %g MPa; the half-plane's elastic fields" % (
        scene.title or os.path.basename(args.scene), k, fatigue["dang_van_a"], fatigue["dang_van_limit"],
        fatigue["shear_fatigue_limit"])
    draw(rows, point, title, os.path.join(args.out, PNG))
    if point:
        p, mu = point
        if mu > mus[-1]:
            print("rcf-map: the point's mu = %g lies beyond --mu-max %g" % (mu, mus[-1]), file=sys.stderr)
        else:
            print("rcf-map: k = %.4g MPa (the lowest yield stress / sqrt 3)" % k)
            print("rcf-map: p0/k = %.3g at mu = %.3g: %s (Johnson); FI_surf = %.3g (%s); FI_sub/tau_e = %.3g, "
                  "Dang Van/tau_w = %.3g on the elastic cycle (> 1: initiation)" % (
                      p, mu, region(p, mu, {key: interpolated(rows, mu, key) for key in rows[0]}),
                      mu - 1.0 / p if p > 0 else -math.inf, "surface initiation" if mu * p > 1.0 else "no surface",
                      p / interpolated(rows, mu, "fi_sub_limit"), p / interpolated(rows, mu, "dang_van_limit")))
    print("rcf-map: %s, %s" % (os.path.join(args.out, PNG), os.path.join(args.out, CSV)))
    return 0
