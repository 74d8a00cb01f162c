"""Johnson's shakedown limit of a line contact under a sliding traction q = mu p (Contact
Mechanics, ch. 9; Johnson & Jefferis 1963), from Melan's theorem: the load p0/k is below the
limit when one residual stress sigma_x(z) per depth keeps the in-plane yield condition
((sigma_x + rho - sigma_z)/2)^2 + tau_xz^2 <= k^2 at every x of that depth. The elastic stresses
are McEwen's closed forms for the Hertz pressure p0 sqrt(1 - x^2/a^2) and q = mu p (plane strain,
a = 1). Gives 4.0 without friction; with friction the limit falls and, above mu = 0.367, is the
surface limit 1/mu.

With unlimited linear kinematic hardening a back-stress (a deviator per depth) shifts each depth's
cycle as well: the strip shakes down when every depth's path of the in-plane shear
((sigma_x - sigma_z)/2, tau_xz) fits in a circle of radius k, so the limit is 1 / the largest radius
of the paths' smallest enclosing circles (kinematic_shakedown_limit; the alternating plasticity
limit of Johnson's map, Ponter, Hearle & Johnson 1985)."""
import random

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


def _circle_of(points):
    """The circle (centre, radius) through one, two (a diameter) or three points."""
    if len(points) == 1:
        return points[0], 0.0
    if len(points) == 2:
        c = (points[0] + points[1]) / 2.0
        return c, float(np.hypot(*(points[0] - c)))
    (ax, ay), (bx, by), (cx, cy) = points
    d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    if abs(d) < 1e-300:  # collinear: the farthest pair's
        pairs = [(points[i], points[j]) for i in range(3) for j in range(i + 1, 3)]
        return max((_circle_of(list(p)) for p in pairs), key=lambda cr: cr[1])
    ux = ((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay) + (cx * cx + cy * cy) * (ay - by)) / d
    uy = ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx) + (cx * cx + cy * cy) * (bx - ax)) / d
    c = np.array([ux, uy])
    return c, float(np.hypot(*(points[0] - c)))


def enclosing_radius(points, seed=0):
    """Radius of the smallest circle enclosing 2-D points (Welzl's algorithm, iterative form: each
    point outside the circle so far is on the boundary of the circle of the points before it)."""
    pts = [np.asarray(p, dtype=float) for p in points]
    random.Random(seed).shuffle(pts)
    c, r = pts[0], 0.0
    tol = 1e-12
    for i, p in enumerate(pts):
        if np.hypot(*(p - c)) <= r + tol:
            continue
        c, r = p, 0.0
        for j in range(i):
            q = pts[j]
            if np.hypot(*(q - c)) <= r + tol:
                continue
            c, r = _circle_of([p, q])
            for k in range(j):
                if np.hypot(*(pts[k] - c)) > r + tol:
                    c, r = _circle_of([p, q, pts[k]])
    return r


def _hull(points):
    """The convex hull's vertices (Andrew's monotone chain): the enclosing circle's candidates."""
    pts = sorted(set(map(tuple, np.round(points, 15))))
    if len(pts) < 3:
        return np.array(pts)

    def half(seq):
        out = []
        for p in seq:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (p[1] - out[-2][1])
                                     - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])) <= 0.0:
                out.pop()
            out.append(p)
        return out
    return np.array(half(pts)[:-1] + half(reversed(pts))[:-1])


def kinematic_shakedown_limit(mu, depths=np.linspace(0.0, 2.0, 201), x=np.linspace(-6.0, 6.0, 1201)):
    """p0/k above which a linearly kinematically hardening strip yields every pass: 1 / the largest,
    over the depths, radius of the smallest circle enclosing the depth's in-plane shear path."""
    largest = 0.0
    for z in depths:
        sx, sz, t = mcewen(x, z, mu)
        path = np.column_stack(((sx - sz) / 2.0, t))
        largest = max(largest, enclosing_radius(_hull(path)))
    return 1.0 / largest


def von_mises_surface_limit(mu, nu, x=np.linspace(-4.0, 4.0, 2001), tol=1e-3):
    """Melan's limit p0/k at the surface itself for a von Mises strip in plane strain: the elastic
    out-of-plane stress nu (sigma_x + sigma_z) stays in the cycle, and the residual stresses rho_x
    and the out-of-plane rho_y are one constant each along the surface (k = sigma_y / sqrt(3)). The
    whole contact is critical at once (((sigma_x - sigma_z)/2)^2 + tau^2 = (mu p0)^2 all along it),
    so the out-of-plane stress, which varies along it, lowers the limit below Johnson's 1/mu unless
    nu = 0.5. Bisection on p0/k; the residual stresses by a shrinking grid search."""
    sx, sz, t = mcewen(x, 0.0, mu)
    sy = nu * (sx + sz)

    def worst(load, rx, ry):  # the largest J2 / k^2 along the surface
        a, b, c = load * sx + rx, load * sz, load * sy + ry
        return np.max(((a - b) ** 2 + (b - c) ** 2 + (c - a) ** 2) / 6.0 + (load * t) ** 2)

    def shakes_down_at(load):
        rx = ry = 0.0
        span = 3.0 * load
        for _ in range(12):
            grid = np.linspace(-span, span, 9)
            value, rx, ry = min((worst(load, rx + u, ry + v), rx + u, ry + v) for u in grid for v in grid)
            span /= 2.5
        return value <= 1.0

    lo, hi = 0.1, 1.5 / max(mu, 1e-3)
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if shakes_down_at(mid) else (lo, mid)
    return lo
