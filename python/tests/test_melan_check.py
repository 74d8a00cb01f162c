"""rollerpy's side of Melan's bound: melan-check scales every initial yield stress of a scene
(the limit scales with them at a fixed load), and the shakedown map's line comes from
`roller shakedown-limit` at each traction."""
import os

import pytest

from rollerpy.paths import PROBLEMS
from rollerpy.plots.shakedown_map import melan_line
from rollerpy.validation.melan_check import scaled_yield


def test_scaled_yield_scales_the_yield_stress_and_its_profile():
    pairs = dict(scaled_yield(os.path.join(PROBLEMS, "shakedown_case_hardened.toml"), 0.5))
    assert float(pairs["material.yield_stress"]) == pytest.approx(888.2312 / 2)
    assert pairs["material.yield_profile"] == "[[0.0, 888.2312], [1.0, 888.2312], [3.0, 444.1156]]"


def test_scaled_yield_refuses_layers_with_their_own_yield_stress(tmp_path):
    scene = tmp_path / "layered.toml"
    scene.write_text('[material]\nyield_stress = 500.0\n[[layer]]\nthickness = 1.0\nyield_stress = 900.0\n')
    with pytest.raises(SystemExit, match="layer"):
        scaled_yield(str(scene), 2.0)


def test_melan_line_falls_with_the_traction(roller):
    scene = os.path.join(PROBLEMS, "shakedown_thin_strip.toml")
    frictionless, sliding = melan_line(roller, scene, [0.0, 0.2])
    assert frictionless == pytest.approx(4.0, rel=0.01)  # Johnson's 4.0: the strip is 5a thick
    assert sliding == pytest.approx(3.2, rel=0.01)
