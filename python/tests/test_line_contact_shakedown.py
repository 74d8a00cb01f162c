"""Johnson's shakedown limit of a line contact (rollerpy.line_contact_shakedown), which
the shakedown map draws: McEwen's stresses meet the classical values (the surface tractions, the
largest orthogonal shear 0.25 p0 at z = 0.5a and principal shear 0.30 p0 at z = 0.78a of the
frictionless contact) and the limit is Johnson's 4.0 without friction and the surface limit 1/mu
at mu = 0.5."""
import numpy as np
import pytest

from rollerpy.line_contact_shakedown import mcewen, shakedown_limit


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
