"""Johnson's shakedown limit of a line contact (rollerpy.line_contact_shakedown), which
the shakedown map draws: McEwen's stresses meet the classical values (the surface tractions, the
largest orthogonal shear 0.25 p0 at z = 0.5a and principal shear 0.30 p0 at z = 0.78a of the
frictionless contact) and the limit is Johnson's 4.0 without friction and the surface limit 1/mu
at mu = 0.5."""
import os
import subprocess

import numpy as np
import pytest

from rollerpy.line_contact_shakedown import (kinematic_shakedown_limit, mcewen, shakedown_limit,
                                             von_mises_surface_limit)
from rollerpy.outputs import read_rows
from rollerpy.paths import PROBLEMS


def test_surface_tractions():
    x = np.linspace(-0.95, 0.95, 39)
    for mu in (0.0, 0.3):
        sx, sz, t = mcewen(x, 0.0, mu)
        p = np.sqrt(1.0 - x * x)
        np.testing.assert_allclose(sz, -p, atol=1e-12)
        np.testing.assert_allclose(np.abs(t), mu * p, atol=1e-12)
        np.testing.assert_allclose(sx, -p + 2.0 * mu * x, atol=1e-12)


def test_frictionless_subsurface_shears():
    x = np.linspace(-3.0, 3.0, 6001)
    orthogonal = [(np.max(np.abs(mcewen(x, z, 0.0)[2])), z) for z in np.linspace(0.05, 2.0, 391)]
    tau, z = max(orthogonal)
    assert tau == pytest.approx(0.25, abs=5e-5)
    assert z == pytest.approx(0.5, abs=0.006)
    depths = np.linspace(0.05, 2.0, 1951)
    sx, sz, t = mcewen(0.0, depths, 0.0)
    principal = np.sqrt(((sx - sz) / 2.0) ** 2 + t * t)
    assert np.max(principal) == pytest.approx(0.300, abs=5e-4)
    assert depths[np.argmax(principal)] == pytest.approx(0.78, abs=0.01)


def test_limits():
    assert shakedown_limit(0.0) == pytest.approx(4.0, abs=2e-3)
    assert shakedown_limit(0.5) == pytest.approx(2.0, abs=2e-3)
    assert shakedown_limit(0.2) < shakedown_limit(0.1)
    # Johnson's 3.56, 3.20, 2.89 (Contact Mechanics, ch. 9) to the digits he gives.
    for mu, limit in ((0.1, 3.56), (0.2, 3.20), (0.3, 2.89)):
        assert shakedown_limit(mu) == pytest.approx(limit, rel=5e-3)


def test_equilibrium():
    """The stresses satisfy equilibrium inside the solid (central differences; McEwen's tau_xz has
    the opposite sign of the x-z frame's, hence the minus signs). The traction's sigma_z once had
    the wrong sign, which the surface values and the frictionless limits do not see."""
    h = 1e-5
    for mu in (0.0, 0.3):
        for x, z in ((0.3, 0.4), (-1.2, 0.5), (1.5, 0.8), (0.0, 1.3)):
            dsx_dx = (mcewen(x + h, z, mu)[0] - mcewen(x - h, z, mu)[0]) / (2 * h)
            dt_dz = (mcewen(x, z + h, mu)[2] - mcewen(x, z - h, mu)[2]) / (2 * h)
            dt_dx = (mcewen(x + h, z, mu)[2] - mcewen(x - h, z, mu)[2]) / (2 * h)
            dsz_dz = (mcewen(x, z + h, mu)[1] - mcewen(x, z - h, mu)[1]) / (2 * h)
            assert dsx_dx - dt_dz == pytest.approx(0.0, abs=1e-6)
            assert dsz_dz - dt_dx == pytest.approx(0.0, abs=1e-6)


def test_kinematic_and_von_mises_surface_limits():
    """The alternating plasticity limit of linear kinematic hardening is 4.0 without friction and the
    surface's 1/mu above mu ~ 0.26; a von Mises strip's surface limit is 1/mu at nu = 0.5 and lies
    below it at nu = 0.3, where the elastic out-of-plane stress varies along the contact."""
    coarse = dict(depths=np.linspace(0.0, 1.5, 61), x=np.linspace(-6.0, 6.0, 481))
    assert kinematic_shakedown_limit(0.0, **coarse) == pytest.approx(4.0, rel=2e-3)
    assert kinematic_shakedown_limit(0.2, **coarse) == pytest.approx(3.945, rel=3e-3)
    for mu in (0.3, 0.5):
        assert kinematic_shakedown_limit(mu, **coarse) == pytest.approx(1.0 / mu, rel=2e-3)
    assert von_mises_surface_limit(0.5, 0.4999) == pytest.approx(2.0, rel=2e-3)
    assert von_mises_surface_limit(0.5, 0.3) == pytest.approx(1.881, rel=3e-3)


def map_of(roller, tmp_path, name, *sets):
    folder = str(tmp_path / name)
    args = [roller, "shakedown-limit", os.path.join(PROBLEMS, "shakedown_kinematic_p45.toml"), "--map", folder,
            "--no-plot"]
    for s in sets:
        args += ["--set", s]
    r = subprocess.run(args, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    return read_rows(os.path.join(folder, "shakedown_limit_map.csv"))


def test_roller_map_meets_the_half_plane_limits_on_the_shipped_mesh(roller, tmp_path):
    """roller shakedown-limit --map on the shipped strip (10 elements across a) against the
    half-plane's limits from McEwen's stresses, within 1 % from q/p = 0 to 0.5: Melan's bound of
    the von Mises strip (nu = 0.3: Johnson's in-plane subsurface limit, then the surface's von
    Mises limit), and at nu = 0.49 (the out-of-plane stress the in-plane mean) Johnson's map itself
    with its surface branch 1/mu and the kinematic bound's alternating plasticity limit."""
    coarse = dict(depths=np.linspace(0.0, 1.5, 61), x=np.linspace(-6.0, 6.0, 481))
    for row in map_of(roller, tmp_path, "nu03"):
        mu = float(row["q_over_p"])
        expected = min(shakedown_limit(mu), von_mises_surface_limit(mu, 0.3)) if mu > 0 else shakedown_limit(0.0)
        assert float(row["elastic_p0_over_k"]) == pytest.approx(expected, rel=0.01), row
        assert row["elastic_mode"] == ("surface" if mu >= 0.35 else "subsurface"), row
    for row in map_of(roller, tmp_path, "nu049", "material.nu=0.49"):
        mu = float(row["q_over_p"])
        johnson = min(shakedown_limit(mu), 1.0 / mu) if mu > 0 else shakedown_limit(0.0)
        assert float(row["elastic_p0_over_k"]) == pytest.approx(johnson, rel=0.01), row
        kinematic = kinematic_shakedown_limit(mu, **coarse)
        assert float(row["kinematic_p0_over_k"]) == pytest.approx(kinematic, rel=0.01), row
