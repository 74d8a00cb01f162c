"""Johnson's shakedown limit of a line contact under a sliding traction q = mu p (Contact
Mechanics, ch. 9; Johnson & Jefferis 1963), from Melan's theorem: the load p0/k is below the
limit when one residual stress sigma_x(z) per depth keeps the in-plane yield condition
((sigma_x + rho - sigma_z)/2)^2 + tau_xz^2 <= k^2 at every x of that depth. The elastic stresses
are McEwen's closed forms for the Hertz pressure p0 sqrt(1 - x^2/a^2) and q = mu p (plane strain,
a = 1). Gives 4.0 without friction; with friction the limit falls and, above mu = 0.367, is the
surface limit 1/mu."""
import numpy as np


def mcewen(x, z, mu):
    """sigma_x, sigma_z, tau_xz per unit p0 at (x, z), z >= 0 into the solid, a = 1."""
    r = 1.0 - x * x + z * z
    s = np.sqrt(r * r + 4.0 * x * x * z * z)
    m = np.sqrt(np.maximum(0.5 * (s + r), 0.0))
    n = np.sign(x) * np.sqrt(np.maximum(0.5 * (s - r), 0.0))
    d = m * m + n * n
    d = np.where(d == 0.0, 1e-300, d)
    sx = -(m * (1.0 + (z * z + n * n) / d) - 2.0 * z)
    sz = -m * (1.0 - (z * z + n * n) / d)
    t = n * (m * m - z * z) / d
    sx += -mu * (n * (2.0 - (z * z - m * m) / d) - 2.0 * x)
    sz += mu * n * (m * m - z * z) / d
    t += -mu * (m * (1.0 + (z * z + n * n) / d) - 2.0 * z)
    return sx, sz, t


def shakes_down(load, stresses):
    """Melan's condition at the load p0/k for the elastic stresses (per unit p0) on a grid of
    depths (rows) by x (columns)."""
    sx, sz, t = stresses
    lt = load * t
    if np.max(np.abs(lt)) > 1.0:
        return False
    centre, radius = load * (sx - sz) / 2.0, np.sqrt(1.0 - lt * lt)
    # Per depth, one rho/2 must fit every x: the largest lower bound below the smallest upper one.
    return bool(np.all(np.max(-radius - centre, axis=1) <= np.min(radius - centre, axis=1) + 1e-12))


def shakedown_limit(mu, tol=1e-4):
    """Johnson's elastic shakedown limit p0/k for the traction coefficient mu (bisection)."""
    x, z = np.meshgrid(np.linspace(-5.0, 5.0, 4001), np.linspace(0.0, 3.0, 601))
    stresses = mcewen(x, z, mu)
    lo, hi = 0.5, 6.0
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if shakes_down(mid, stresses) else (lo, mid)
    return lo
