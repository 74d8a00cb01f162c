"""Carter's steady rolling on the stationary pass (docs/validation.md, "Carter on the stationary
pass"): problems/carter.toml's elastic strip held at P = 10 600 N/mm and rolled with the creep
0.0013 in one stationary pass; the traction found by Coulomb's law against Carter's, whose stick
zone c = a - s R / mu touches the leading edge. From the checkout's root:
PYTHONPATH=python /usr/bin/python3 docs/examples/stationary_carter.py [FIGURE]"""
import sys
import tomllib

import matplotlib
import numpy as np
import rollerpy

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

creep, mu, radius = 0.0013, 0.15, 100.0
scene = tomllib.load(open("problems/carter.toml", "rb"))
scene["passes"] = {"method": "stationary", "count": 1}
scene["roller"]["path"] = [{"steps": [1, 4], "fy": 10600.0},
                           {"steps": [5, 94], "dx": 34.0, "fy": 10600.0, "slip": creep}]
fig, ax = plt.subplots(figsize=(6.4, 3.8))
for refine, marker in [(1, "o"), (2, "s")]:
    run = rollerpy.run(scene, set={"mesh.refine": refine})
    contact = run.contact  # contact.csv's columns, the pass's contact
    x, p, q = (np.asarray(contact[k], dtype=float) for k in ("x", "p_n", "p_t"))
    on = p > 0
    x, p, q = x[on], p[on], q[on]
    c2 = np.polyfit(x, p**2, 2)  # p^2 = p0^2 (1 - (x - x0)^2 / a^2): a parabola
    x0 = -c2[1] / (2 * c2[0])
    p0 = np.sqrt(np.polyval(c2, x0))
    a = p0 / np.sqrt(-c2[0])
    c = a - creep * radius / mu
    xs = np.linspace(-a, a, 401)
    carter = mu * p0 * np.sqrt(1 - (xs / a) ** 2)
    stick = np.abs(xs - (a - c)) < c
    carter[stick] -= mu * (c / a) * p0 * np.sqrt(1 - ((xs[stick] - (a - c)) / c) ** 2)
    if refine == 1:
        ax.plot(xs / a, mu * p0 * np.sqrt(1 - (xs / a) ** 2) / p0, "k:", lw=0.8, label="μp")
        ax.plot(xs / a, carter / p0, "k-", lw=1.0, label=f"Carter, c/a = {c / a:.3f}")
    ax.plot((x - x0) / a, q / p0, marker, ms=3, mfc="none", label=f"stationary pass, refine {refine}")
    print(f"refine {refine}: {len(x)} nodes in contact, a = {a:.4f} mm, p0 = {p0:.1f} MPa, Carter's c/a = {c / a:.4f}")
ax.set(xlabel="x / a (the roller rolls towards +x)", ylabel="q / p0", xlim=(-1.1, 1.1))
ax.legend(fontsize=8, loc="upper left")
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "stationary_carter.png", dpi=120, bbox_inches="tight")
