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


def sweep(args):
    os.makedirs(args.out, exist_ok=True)

    with open(args.scene, "rb") as f:
        scene = tomllib.load(f)
    E, nu = scene["material"]["E"], scene["material"].get("nu", 0.3)
    R, mu = scene["roller"]["radius"], scene["contact"]["friction"]
    segments = scene["roller"]["path"]
    n_press = max(s["steps"][1] for s in segments if float(s.get("dx", 0.0)) == 0.0)
    e_star = E / (1.0 - nu * nu)
    backends = args.backends.split(",")

    # Press-in alone: a0 sets the creeps.
    press = os.path.join(args.out, "press_in")
    if not args.reuse:
        run(args, press, backends[0], [], steps=n_press)
    m0 = measure(read_rows(os.path.join(press, "contact.csv")), n_press, mu)
    a0 = m0["a"]
    print("press-in: a0 = %.4f mm, mu a0/R = %.4e" % (a0, mu * a0 / R))

    if args.traction:
        fractions = QUICK_TRACTIONS if args.quick else TRACTIONS
        p_press = float(read_rows(os.path.join(press, "roller.csv"))[-1]["fy"])
    else:
        fractions = QUICK_FRACTIONS if args.quick else FRACTIONS
    tag = "traction_" if args.traction else ""
    results = []
    for backend in backends:
        for k, frac in enumerate(fractions):
            out = os.path.join(args.out, "%s%s_%d" % (tag, backend, k))
            if args.traction:
                override = traction_override(segments, -frac * mu * p_press)
            else:
                creep = round(frac * mu * a0 / R, 7)
                override = path_override(segments, creep)
            if args.reuse:  # the run's own wall time
                wall = float(read_summary(out)["wall_s"])
            else:
                wall = run(args, out, backend, [override])
            roller = read_rows(os.path.join(out, "roller.csv"))
            contact = read_rows(os.path.join(out, "contact.csv"))
            last = int(roller[-1]["step"])
            fx, fy = float(roller[-1]["fx"]), float(roller[-1]["fy"])
            P, Q = fy, abs(fx)
            q_ratio = Q / (mu * P)
            m = measure(contact, last, mu)
            a = m["a"]
            # One contact width 2a of rolling before the last step.
            xc_last = float(roller[-1]["xc"])
            earlier = min(roller, key=lambda r: abs(float(r["xc"]) - (xc_last - 2.0 * a)))
            s_prev = int(earlier["step"])
            q_prev = abs(float(earlier["fx"])) / (mu * float(earlier["fy"]))
            m_prev = measure(contact, s_prev, mu)
            if args.traction:
                creep = measured_creep(roller, s_prev)
            xi_norm = creep * R / (mu * a)
            c_carter = a * math.sqrt(max(1.0 - q_ratio, 0.0))
            row = dict(
                backend=backend, creep=creep, xi_norm=xi_norm, P=P, Q=Q, q_ratio=q_ratio,
                q_theory=float(carter_ratio(xi_norm)), q_err=q_ratio - float(carter_ratio(xi_norm)),
                a_fit=a, a_hertz=math.sqrt(4.0 * P * R / (math.pi * e_star)), p0_fit=m["p0"],
                p0_hertz=a * e_star / (2.0 * R), x0_minus_xc=m["x0"] - xc_last,
                n_stick=m["n_stick"], c_moment=m["c"], d_moment=m["d"], c_parabola=m["c_parabola"],
                d_parabola=m["d_parabola"], c_status=m["c_status"],
                d_status=m["d_status"], leading_edge=m["d"] + m["c"],
                c_carter=c_carter,
                c_err=(m["c"] - c_carter) / c_carter if m["c"] > 0.0 and c_carter > 0.0 else float("nan"),
                c_from_creep=a * max(1.0 - xi_norm, 0.0),
                dq_last_2a=(q_ratio - q_prev) / q_ratio,
                dc_last_2a=(m["c"] - m_prev["c"]) / m["c"] if m["c"] > 0.0 else float("nan"),
                rolled=xc_last - float(next(r for r in roller if int(r["step"]) == n_press)["xc"]),
                steps=last, wall_s=wall,
                creep_carter=mu * a / R * (1.0 - math.sqrt(max(1.0 - q_ratio, 0.0))))
            results.append((row, m, frac))
            print("%-7s xi=%.3e xiR/(mu a)=%.3f  Q/(mu P)=%.4f (Carter %.4f)  a=%.4f  c=%.4f (Carter %.4f, %+.1f %%) "
                  "d+c=%.3f  c_parabola=%.3f c_status=%.3f  dQ,dc over last 2a: %+.2f %%, %+.2f %%  %.1f s"
                  % (backend, creep, xi_norm, q_ratio, row["q_theory"], a, m["c"], c_carter, 100 * row["c_err"],
                     row["leading_edge"], m["c_parabola"], m["c_status"], 100 * row["dq_last_2a"],
                     100 * row["dc_last_2a"], wall),
                  flush=True)

    keys = list(results[0][0].keys())
    with open(os.path.join(args.out, "carter%s.csv" % ("_traction" if args.traction else "")), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for row, _, _ in results:
            w.writerow({k: ("%.6g" % v if isinstance(v, float) else v) for k, v in row.items()})

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.8))
    xs = np.linspace(0.0, 1.6, 200)
    ax1.plot(xs, carter_ratio(xs), "k-", label="Carter: 1 − (1 − ξR/(μa))²")
    markers = {"ipopt": ("o", "C0"), "penalty": ("x", "C3")}
    for backend in backends:
        pts = [(r["xi_norm"], r["q_ratio"]) for r, _, _ in results if r["backend"] == backend]
        mk, col = markers.get(backend, ("s", "C2"))
        ax1.plot([p[0] for p in pts], [p[1] for p in pts], mk, color=col, ms=8, mfc="none" if mk == "o" else col,
                 label=backend)
    ax1.set_xlabel("creep ξR/(μa)")
    ax1.set_ylabel("Q/(μP)")
    ax1.set_xlim(0.0, 1.6)
    ax1.set_ylim(0.0, 1.05)
    ax1.grid(alpha=0.3)
    ax1.legend(loc="lower right")
    ax1.set_title("Creep (measured) under a prescribed traction" if args.traction
                  else "Traction against creep (last step)")

    target = min(fractions, key=lambda f: abs(f - PROFILE_FRACTION))
    xa = np.linspace(-1.0, 1.0, 401)
    for row, m, frac in results:
        if frac != target:
            continue
        a, p0 = m["a"], m["p0"]
        xn = (m["x"] - (m["x0"])) / a
        on = m["on"]
        mk, col = markers.get(row["backend"], ("s", "C2"))
        ax2.plot(xn[on], m["t"][on] / (mu * p0), mk + "-", color=col, ms=5, lw=0.8,
                 mfc="none" if mk == "o" else col, label="p_t/(μp0), %s" % row["backend"])
        if row["backend"] == backends[0]:
            ax2.plot(xn[on], m["p"][on] / p0, ".", color="0.5", ms=4, label="p_n/p0, %s" % row["backend"])
            c = row["c_carter"]
            ax2.plot(xa, carter_traction(xa * a, a, c, p0, mu) / (mu * p0), "k-",
                     label="Carter q(x), c/a = √(1 − Q/μP) = %.3f" % (c / a))
            ax2.plot(xa, np.sqrt(1.0 - xa ** 2), "k:", lw=0.8, label="μp (Hertz)")
            ax2.axvspan((a - 2 * c) / a, 1.0, color="C2", alpha=0.08, label="Carter's stick zone")
            ax2.set_title("Traction profile, ξR/(μa) = %.2f (roller moving to +x)" % row["xi_norm"])
    ax2.set_xlabel("(x − x0)/a")
    ax2.set_ylabel("p_t/(μp0), p_n/p0")
    ax2.set_xlim(-1.15, 1.15)
    ax2.set_ylim(0.0, 1.05)
    ax2.grid(alpha=0.3)
    ax2.legend(loc="upper left", fontsize=7)
    fig.tight_layout()
    name = os.path.join(args.out, "carter%s" % ("_traction" if args.traction else ""))
    fig.savefig(name + ".png", dpi=110)
    print("wrote %s.csv and %s.png" % (name, name))
    return 0
