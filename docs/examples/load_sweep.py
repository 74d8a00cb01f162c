"""A load sweep in the Python process (docs/python.md, "roller in process"): the Hertz scene
pressed by three forces (given as Hertz peak pressures), the contact pressure against Hertz's. From the checkout's root:
PYTHONPATH=python /usr/bin/python3 docs/examples/load_sweep.py [FIGURE]"""
import sys
import tomllib

import matplotlib
import numpy as np
import rollerpy

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

scene = tomllib.load(open("problems/hertz.toml", "rb"))
del scene["roller"]["path"][0]["dy"]  # pressed by a force (its Hertz p0) instead of a depth
e_star = 2.1e5 / (1 - 0.3**2)
fig, ax = plt.subplots(figsize=(6, 3.6))
for p0 in [1200, 2000, 2800]:
    run = rollerpy.run(scene, set={"roller.path[0].p0": p0})
    x = run.mesh.points[:, 0] - 100.0
    p = run.field("contact_pressure")
    a = np.sqrt(4 * run.roller["fy"][-1] * 100.0 / (np.pi * e_star))  # Hertz, at the force reached
    xs = np.linspace(-a, a, 201)
    ax.plot(xs, p0 * np.sqrt(1 - (xs / a) ** 2), "k-", lw=0.8)
    ax.plot(x[p > 0], p[p > 0], "o", ms=3, label=f"p0 = {p0} MPa: peak {p.max():.0f} MPa")
ax.set(xlabel="x − x_roller [mm]", ylabel="contact pressure [MPa]", xlim=(-3, 3), ylim=(0, 3900))
ax.legend(title="roller (dots), Hertz (lines)", fontsize=8, loc="upper right")
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "load_sweep.png", dpi=120, bbox_inches="tight")
