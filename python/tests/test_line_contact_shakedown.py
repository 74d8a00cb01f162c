#!/usr/bin/python3
"""Johnson's shakedown limit of a line contact (scripts/line_contact_shakedown.py), which the
shakedown map draws: McEwen's stresses meet the classical values (the surface tractions, the
largest orthogonal shear 0.25 p0 at z = 0.5a and principal shear 0.30 p0 at z = 0.78a of the
frictionless contact) and the limit is Johnson's 4.0 without friction and the surface limit 1/mu
at mu = 0.5."""
import os
import sys
import unittest

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "scripts"))
from line_contact_shakedown import mcewen, shakedown_limit  # noqa: E402


class LineContact(unittest.TestCase):
    def test_surface_tractions(self):
        x = np.linspace(-0.95, 0.95, 39)
        for mu in (0.0, 0.3):
            sx, sz, t = mcewen(x, 0.0, mu)
            p = np.sqrt(1.0 - x * x)
            np.testing.assert_allclose(sz, -p, atol=1e-12)
            np.testing.assert_allclose(np.abs(t), mu * p, atol=1e-12)
            np.testing.assert_allclose(sx, -p + 2.0 * mu * x, atol=1e-12)

    def test_frictionless_subsurface_shears(self):
        x = np.linspace(-3.0, 3.0, 6001)
        orthogonal = [(np.max(np.abs(mcewen(x, z, 0.0)[2])), z) for z in np.linspace(0.05, 2.0, 391)]
        tau, z = max(orthogonal)
        self.assertAlmostEqual(tau, 0.25, places=4)
        self.assertAlmostEqual(z, 0.5, delta=0.006)
        sx, sz, t = mcewen(0.0, np.linspace(0.05, 2.0, 1951), 0.0)
        principal = np.sqrt(((sx - sz) / 2.0) ** 2 + t * t)
        self.assertAlmostEqual(np.max(principal), 0.300, places=3)
        self.assertAlmostEqual(np.linspace(0.05, 2.0, 1951)[np.argmax(principal)], 0.78, delta=0.01)

    def test_limits(self):
        self.assertAlmostEqual(shakedown_limit(0.0), 4.0, delta=2e-3)
        self.assertAlmostEqual(shakedown_limit(0.5), 2.0, delta=2e-3)
        self.assertLess(shakedown_limit(0.2), shakedown_limit(0.1))


if __name__ == "__main__":
    unittest.main(verbosity=2)
