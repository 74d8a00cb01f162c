"""Carter's steady rolling with creep: runs problems/carter.toml for several creeps with both
contact backends and compares with Carter's theory (docs/validation.md, "Carter: steady rolling
with creep").

usage: ./rollerpy carter [--out DIR] [--roller BIN] [--refine K] [--quick]
                        [--backends ipopt,penalty] [--scene FILE] [--traction]

Theory (rigid cylinder on an elastic half-plane, plane strain, E* = E/(1 - nu^2), normal and
tangential problems decoupled): a = sqrt(4 P R/(pi E*)), p0 = 2P/(pi a) = a E*/(2R);
q(x) = mu p0 sqrt(1 - x^2/a^2) - mu p0 (c/a) sqrt(1 - (x - d)^2/c^2), stick zone |x - d| <= c at the
leading edge, d = a - c, c/a = sqrt(1 - Q/(mu P)); the stick zone's surface strain equals the creep:
|xi| = (mu a/R)(1 - c/a), i.e. Q/(mu P) = 1 - (1 - |xi| R/(mu a))^2 below full sliding.

The creep is set by overriding the whole roller.path array (--set roller.path=[...]) with the
scene's segments, the slip of every rolling segment replaced. Creeps are chosen as fractions of
mu a0/R, a0 the contact half-width of the press-in (a first run of the press-in steps alone).

Measured from the last step: P = fy, Q = |fx| (roller.csv); from contact.csv the contact
half-width a and centre x0 from a least-squares fit of p_n^2 = p0^2 (1 - (x - x0)^2/a^2) over the
nodes carrying pressure; the stick zone from the moments of the traction deficit
w(x) = mu p_n - |p_t|, which vanishes in the slip zone and in Carter's solution equals
mu p0 (c/a) sqrt(1 - (x - d)^2/c^2) on the stick zone: its centroid is the zone's centre d, its
standard deviation c/2, so c = 2 std(w). Sums over all contact nodes, so the node-to-node scatter
of the stick traction averages out and the edges need no node classification. Written beside it:
c_parabola (a least-squares parabola through w^2 over the nodes the backend reports as sticking,
its roots the edges) and c_status (outermost sticking nodes, half a spacing added on each side);
both are cruder, see docs/validation.md. The leading edge of the stick zone is d + c (= a if the
zone touches the leading contact edge). Steadiness: Q/(mu P) and c one contact width 2a of
rolling before the last step.

--traction poses Carter's problem the other way round: the roller turns at the rolling rate
(slip 0) while a horizontal force fx = -(Q/(mu P)) mu P0 acts on it (roller.path fx, ramped over
the build-up segment, P0 the press-in's force), so that its centre x is an unknown; the creep is
then an outcome, s = d(load_offset_x)/d(xc) over the last contact width 2a (roller.csv), compared
with Carter's s = (mu a/R)(1 - sqrt(1 - Q/(mu P))). Tractions Q/(mu P) = 0.36, 0.64, 0.84, 0.96
(the creeps 0.2 ... 0.8 mu a/R); writes DIR/carter_traction.csv and .png.

Writes DIR/carter.csv and DIR/carter.png (and keeps the runs in DIR/<backend>_<k>/, each with its
log DIR/<backend>_<k>.log).
"""
import csv
import math
import os
import sys
import tomllib
from dataclasses import dataclass

import numpy as np

from ..command import parser
from ..outputs import contact_profile, read_rows, read_summary
from ..paths import DEFAULT_ROLLER, PROBLEMS, ROOT
from ..plots import plt
from ..runner import RunFailed, contact_option, roller_command, run as run_roller
FRACTIONS = [0.2, 0.4, 0.6, 0.8, 1.5]   # creep / (mu a0 / R)
QUICK_FRACTIONS = [0.4, 0.8]
TRACTIONS = [0.36, 0.64, 0.84, 0.96]     # Q/(mu P) = 1 - (1 - f)^2 for f = 0.2, 0.4, 0.6, 0.8
QUICK_TRACTIONS = [0.64, 0.96]
PROFILE_FRACTION = 0.6
MARKERS = {"ipopt": ("o", "C0"), "penalty": ("x", "C3")}   # backend: marker, colour
OTHER_MARKER = ("s", "C2")


def carter_ratio(xi_norm):
    """Q/(mu P) against |xi| R/(mu a)."""
    xi_norm = np.minimum(np.abs(xi_norm), 1.0)
    return 1.0 - (1.0 - xi_norm) ** 2


def carter_traction(x, a, c, p0, mu):
    """Carter's q(x) with the stick zone at the leading edge x = +a (roller moving to +x)."""
    d = a - c
    q = mu * p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))
    if c > 0.0:
        q -= mu * p0 * (c / a) * np.sqrt(np.clip(1.0 - ((x - d) / c) ** 2, 0.0, None))
    return q


def fit_parabola(x, y):
    """y = A (1 - (x - x0)^2 / w^2) by least squares: returns x0, w, A."""
    c2, c1, c0 = np.polyfit(x, y, 2)
    b = -c2
    if b <= 0.0:
        return float("nan"), float("nan"), float("nan")
    x0 = c1 / (2.0 * b)
    amp = c0 + b * x0 * x0
    return x0, math.sqrt(max(amp, 0.0) / b), amp


def zone_extent(x, member):
    """The zone's half-width and centre, its boundary halfway to the next node outside it."""
    idx = np.where(member)[0]
    if len(idx) == 0:
        return 0.0, float("nan")
    lo, hi = idx[0], idx[-1]
    left = 0.5 * (x[lo] + x[lo - 1]) if lo > 0 else x[lo]
    right = 0.5 * (x[hi] + x[hi + 1]) if hi + 1 < len(x) else x[hi]
    return 0.5 * (right - left), 0.5 * (right + left)


def measure(contact_rows, step, mu):
    profile = contact_profile(contact_rows, step)
    x, p, t, status = profile.x, profile.p_n, profile.p_t, profile.status
    on = p > 1e-3 * p.max()
    x0, a, p0sq = fit_parabola(x[on], p[on] ** 2)
    a_status, _ = zone_extent(x, on)
    stick = on & np.array([s == "stick" for s in status])
    n_stick = int(stick.sum())
    c_status, centre_status = zone_extent(x, stick)
    res = dict(x0=x0, a=a, p0=math.sqrt(p0sq), a_status=a_status, n_stick=n_stick, c_status=c_status,
               d_status=centre_status - x0, c=float("nan"), d=float("nan"), c_parabola=float("nan"),
               d_parabola=float("nan"), x=x, p=p, t=t, on=on)
    if n_stick >= 4:
        idx = np.where(stick)[0]
        g = (mu * p[idx] - np.abs(t[idx])) ** 2
        xs, c, _ = fit_parabola(x[idx], g)
        res.update(c_parabola=c, d_parabola=xs - x0)
    # Moments of the traction deficit w = mu p_n - |p_t| (zero in the slip zone): in Carter's
    # solution w = mu p0 (c/a) sqrt(1 - (x - d)^2/c^2) on the stick zone, so its centroid is d and
    # its variance c^2/4. Uniform node spacing in the track: nodal values weigh equally.
    w = np.where(on, np.clip(mu * p - np.abs(t), 0.0, None), 0.0)
    if w.max() > 1e-3 * mu * res["p0"]:  # else full sliding: no stick zone
        xm = float((w * x).sum() / w.sum())
        var = float((w * (x - xm) ** 2).sum() / w.sum())
        res.update(c=2.0 * math.sqrt(var), d=xm - x0)
    else:
        res.update(c=0.0, d=float("nan"))
    return res


def run(args, out, backend, overrides, steps=None):
    """One run into `out` (its log beside it); returns its wall time, raises RunFailed."""
    options = ["--refine", args.refine] + contact_option(backend)
    for o in overrides:
        options += ["--set", o]
    if steps:
        options += ["--steps", steps]
    return run_roller(roller_command(args.roller, args.scene, out, *options), out + ".log").check().wall_s


def rolling_path(segments, rolling_keys):
    """The scene's path as a --set roller.path override, every rolling segment (dx != 0) given
    rolling_keys instead of its own slip."""
    parts = []
    for s in segments:
        keys = ["steps=[%d,%d]" % tuple(s["steps"])]
        for k in ("dx", "dy"):
            if k in s:
                keys.append("%s=%r" % (k, float(s[k])))
        if float(s.get("dx", 0.0)) != 0.0:
            keys += ["%s=%r" % kv for kv in rolling_keys.items()]
        elif "slip" in s:
            keys.append("slip=%r" % s["slip"])
        parts.append("{" + ",".join(keys) + "}")
    return "roller.path=[" + ",".join(parts) + "]"


def path_override(segments, creep):
    return rolling_path(segments, {"slip": creep})


def traction_override(segments, fx):
    """Turning at the rolling rate (slip 0) under the horizontal force fx on every rolling
    segment (ramped from 0 over the first)."""
    return rolling_path(segments, {"fx": fx})


def measured_creep(roller, s_prev):
    """s = (v - omega R)/v from the centre's drift off its rolling path over steps s_prev...last."""
    first = next(r for r in roller if int(r["step"]) == s_prev)
    last = roller[-1]
    dx = float(last["xc"]) - float(first["xc"])
    return (float(last["load_offset_x"]) - float(first["load_offset_x"])) / dx


def main(argv=None):
    ap = parser("carter", __doc__)
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "carter"))
    ap.add_argument("--roller", default=DEFAULT_ROLLER)
    ap.add_argument("--scene", default=os.path.join(PROBLEMS, "carter.toml"))
    ap.add_argument("--refine", type=int, default=1)
    ap.add_argument("--quick", action="store_true", help="creeps 0.4 and 0.8 of mu a/R only")
    ap.add_argument("--backends", default="ipopt,penalty")
    ap.add_argument("--reuse", action="store_true", help="analyse the runs already in --out instead of running")
    ap.add_argument("--traction", action="store_true", help="prescribe Q (roller.path fx), measure the creep")
    args = ap.parse_args(argv)
    try:
        return sweep(args)
    except RunFailed as e:
        sys.exit(str(e))


@dataclass(frozen=True)
class CarterScene:
    """What the sweep takes from the scene file."""
    e_star: float    # plane-strain modulus E/(1 - nu^2)
    radius: float    # roller radius R
    mu: float        # friction coefficient
    segments: list   # roller.path, the segments the overrides rewrite
    n_press: int     # last step of the press-in (the segments with dx = 0)


def read_scene(path):
    with open(path, "rb") as f:
        scene = tomllib.load(f)
    E, nu = scene["material"]["E"], scene["material"].get("nu", 0.3)
    segments = scene["roller"]["path"]
    return CarterScene(e_star=E / (1.0 - nu * nu), radius=scene["roller"]["radius"],
                       mu=scene["contact"]["friction"], segments=segments,
                       n_press=max(s["steps"][1] for s in segments if float(s.get("dx", 0.0)) == 0.0))


def press_in(args, scene, backend):
    """Runs (or reuses) the press-in alone: returns its half-width a0, which sets the creeps, and
    under --traction its vertical force P0, which sets the tractions (else None)."""
    press = os.path.join(args.out, "press_in")
    if not args.reuse:
        run(args, press, backend, [], steps=scene.n_press)
    a0 = measure(read_rows(os.path.join(press, "contact.csv")), scene.n_press, scene.mu)["a"]
    print("press-in: a0 = %.4f mm, mu a0/R = %.4e" % (a0, scene.mu * a0 / scene.radius))
    p_press = float(read_rows(os.path.join(press, "roller.csv"))[-1]["fy"]) if args.traction else None
    return a0, p_press


def sweep_fractions(args):
    """Creeps / (mu a0/R), or under --traction Q/(mu P0)."""
    if args.traction:
        return QUICK_TRACTIONS if args.quick else TRACTIONS
    return QUICK_FRACTIONS if args.quick else FRACTIONS


def case_override(traction, scene, frac, a0, p_press):
    """The case's roller.path override and its prescribed creep (None under --traction, where the
    creep is measured)."""
    if traction:
        return traction_override(scene.segments, -frac * scene.mu * p_press), None
    creep = round(frac * scene.mu * a0 / scene.radius, 7)
    return path_override(scene.segments, creep), creep


def run_or_reuse(args, out, backend, override):
    """Runs the case unless --reuse; returns the run's own wall time either way."""
    if args.reuse:
        return float(read_summary(out)["wall_s"])
    return run(args, out, backend, [override])


def last_step_measures(roller, contact, mu):
    """Loads and contact at the last step, and the same one contact width 2a of rolling before it
    (the steadiness check)."""
    last = roller[-1]
    fx, fy = float(last["fx"]), float(last["fy"])
    P, Q = fy, abs(fx)
    m = measure(contact, int(last["step"]), mu)
    xc_last = float(last["xc"])
    earlier = min(roller, key=lambda r: abs(float(r["xc"]) - (xc_last - 2.0 * m["a"])))
    s_prev = int(earlier["step"])
    return dict(step=int(last["step"]), xc=xc_last, P=P, Q=Q, q_ratio=Q / (mu * P), m=m, s_prev=s_prev,
                q_prev=abs(float(earlier["fx"])) / (mu * float(earlier["fy"])), m_prev=measure(contact, s_prev, mu))


def carter_row(backend, creep, last, scene, rolled, wall):
    """The case's CSV row: measured loads and zones beside Carter's and Hertz's values."""
    mu, R, e_star = scene.mu, scene.radius, scene.e_star
    m, m_prev, q_ratio = last["m"], last["m_prev"], last["q_ratio"]
    a, P = m["a"], last["P"]
    xi_norm = creep * R / (mu * a)
    c_carter = a * math.sqrt(max(1.0 - q_ratio, 0.0))
    return dict(
        backend=backend, creep=creep, xi_norm=xi_norm, P=P, Q=last["Q"], q_ratio=q_ratio,
        q_theory=float(carter_ratio(xi_norm)), q_err=q_ratio - float(carter_ratio(xi_norm)),
        a_fit=a, a_hertz=math.sqrt(4.0 * P * R / (math.pi * e_star)), p0_fit=m["p0"],
        p0_hertz=a * e_star / (2.0 * R), x0_minus_xc=m["x0"] - last["xc"],
        n_stick=m["n_stick"], c_moment=m["c"], d_moment=m["d"], c_parabola=m["c_parabola"],
        d_parabola=m["d_parabola"], c_status=m["c_status"],
        d_status=m["d_status"], leading_edge=m["d"] + m["c"],
        c_carter=c_carter,
        c_err=(m["c"] - c_carter) / c_carter if m["c"] > 0.0 and c_carter > 0.0 else float("nan"),
        c_from_creep=a * max(1.0 - xi_norm, 0.0),
        dq_last_2a=(q_ratio - last["q_prev"]) / q_ratio,
        dc_last_2a=(m["c"] - m_prev["c"]) / m["c"] if m["c"] > 0.0 else float("nan"),
        rolled=rolled, steps=last["step"], wall_s=wall,
        creep_carter=mu * a / R * (1.0 - math.sqrt(max(1.0 - q_ratio, 0.0))))


def analyse_case(out, backend, creep, scene, traction, wall):
    """Reads one run's outputs: returns its CSV row and its last step's contact measures."""
    roller = read_rows(os.path.join(out, "roller.csv"))
    contact = read_rows(os.path.join(out, "contact.csv"))
    last = last_step_measures(roller, contact, scene.mu)
    if traction:
        creep = measured_creep(roller, last["s_prev"])
    rolled = last["xc"] - float(next(r for r in roller if int(r["step"]) == scene.n_press)["xc"])
    return carter_row(backend, creep, last, scene, rolled, wall), last["m"]


def print_case(row, m):
    print("%-7s xi=%.3e xiR/(mu a)=%.3f  Q/(mu P)=%.4f (Carter %.4f)  a=%.4f  c=%.4f (Carter %.4f, %+.1f %%) "
          "d+c=%.3f  c_parabola=%.3f c_status=%.3f  dQ,dc over last 2a: %+.2f %%, %+.2f %%  %.1f s"
          % (row["backend"], row["creep"], row["xi_norm"], row["q_ratio"], row["q_theory"], row["a_fit"], m["c"],
             row["c_carter"], 100 * row["c_err"], row["leading_edge"], m["c_parabola"], m["c_status"],
             100 * row["dq_last_2a"], 100 * row["dc_last_2a"], row["wall_s"]),
          flush=True)


def run_cases(args, scene, backends, fractions, a0, p_press):
    """Every backend at every fraction, each run (or reused), analysed and printed in turn;
    returns (row, measures, fraction) per case."""
    tag = "traction_" if args.traction else ""
    results = []
    for backend in backends:
        for k, frac in enumerate(fractions):
            out = os.path.join(args.out, "%s%s_%d" % (tag, backend, k))
            override, creep = case_override(args.traction, scene, frac, a0, p_press)
            wall = run_or_reuse(args, out, backend, override)
            row, m = analyse_case(out, backend, creep, scene, args.traction, wall)
            results.append((row, m, frac))
            print_case(row, m)
    return results


def write_csv(path, results):
    keys = list(results[0][0].keys())
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for row, _, _ in results:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in row.items()})


def plot_ratio(ax, results, backends, traction):
    """Left panel: Q/(mu P) against the creep, each backend against Carter's curve."""
    xs = np.linspace(0.0, 1.6, 200)
    ax.plot(xs, carter_ratio(xs), "k-", label="Carter: 1 − (1 − ξR/(μa))²")
    for backend in backends:
        pts = [(r["xi_norm"], r["q_ratio"]) for r, _, _ in results if r["backend"] == backend]
        mk, col = MARKERS.get(backend, OTHER_MARKER)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], mk, color=col, ms=8, mfc="none" if mk == "o" else col,
                label=backend)
    ax.set_xlabel("creep ξR/(μa)")
    ax.set_ylabel("Q/(μP)")
    ax.set_xlim(0.0, 1.6)
    ax.set_ylim(0.0, 1.05)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right")
    ax.set_title("Creep (measured) under a prescribed traction" if traction
                 else "Traction against creep (last step)")


def plot_carter_profile(ax, row, m, mu, xn):
    """The first backend's pressure beside Carter's traction, Hertz's bound and Carter's stick zone."""
    a, p0, on = m["a"], m["p0"], m["on"]
    xa = np.linspace(-1.0, 1.0, 401)
    ax.plot(xn[on], m["p"][on] / p0, ".", color="0.5", ms=4, label="p_n/p0, %s" % row["backend"])
    c = row["c_carter"]
    ax.plot(xa, carter_traction(xa * a, a, c, p0, mu) / (mu * p0), "k-",
            label="Carter q(x), c/a = √(1 − Q/μP) = %.3f" % (c / a))
    ax.plot(xa, np.sqrt(1.0 - xa ** 2), "k:", lw=0.8, label="μp (Hertz)")
    ax.axvspan((a - 2 * c) / a, 1.0, color="C2", alpha=0.08, label="Carter's stick zone")
    ax.set_title("Traction profile, ξR/(μa) = %.2f (roller moving to +x)" % row["xi_norm"])


def plot_profile(ax, results, fractions, backends, mu):
    """Right panel: the traction profiles of the case nearest PROFILE_FRACTION."""
    target = min(fractions, key=lambda f: abs(f - PROFILE_FRACTION))
    for row, m, frac in results:
        if frac != target:
            continue
        xn = (m["x"] - (m["x0"])) / m["a"]
        on = m["on"]
        mk, col = MARKERS.get(row["backend"], OTHER_MARKER)
        ax.plot(xn[on], m["t"][on] / (mu * m["p0"]), mk + "-", color=col, ms=5, lw=0.8,
                mfc="none" if mk == "o" else col, label="p_t/(μp0), %s" % row["backend"])
        if row["backend"] == backends[0]:
            plot_carter_profile(ax, row, m, mu, xn)
    ax.set_xlabel("(x − x0)/a")
    ax.set_ylabel("p_t/(μp0), p_n/p0")
    ax.set_xlim(-1.15, 1.15)
    ax.set_ylim(0.0, 1.05)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=7)


def plot_results(path, results, fractions, backends, mu, traction):
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    plot_ratio(ax1, results, backends, traction)
    plot_profile(ax2, results, fractions, backends, mu)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def sweep(args):
    """The command: the press-in, then every backend at every creep (or traction), CSV and plot."""
    os.makedirs(args.out, exist_ok=True)
    scene = read_scene(args.scene)
    backends = args.backends.split(",")
    a0, p_press = press_in(args, scene, backends[0])
    fractions = sweep_fractions(args)
    results = run_cases(args, scene, backends, fractions, a0, p_press)
    name = os.path.join(args.out, "carter%s" % ("_traction" if args.traction else ""))
    write_csv(name + ".csv", results)
    plot_results(name + ".png", results, fractions, backends, scene.mu, args.traction)
    print("wrote %s.csv and %s.png" % (name, name))
    return 0
