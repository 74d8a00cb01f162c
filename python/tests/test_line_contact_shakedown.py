"""Johnson's shakedown limit of a line contact (rollerpy.validation.line_contact_shakedown), which
the shakedown map draws: McEwen's stresses meet the classical values (the surface tractions, the
largest orthogonal shear 0.25 p0 at z = 0.5a and principal shear 0.30 p0 at z = 0.78a of the
frictionless contact) and the limit is Johnson's 4.0 without friction and the surface limit 1/mu
at mu = 0.5."""
import numpy as np
import pytest

from rollerpy.validation.line_contact_shakedown import mcewen, shakedown_limit


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
