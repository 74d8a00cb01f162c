"""rcf-map on the shipped wheel-rail scene: Johnson's limits of the half-plane where his map has
them (first yield 1/0.300 and shakedown 4.0 without friction, both 1/mu at the surface above
mu = 0.367), the initiation limits as the run's criteria on the unit cycle (linear in the load:
twice tau_e, twice the limit), the scene's load point from its roller, and the command's files."""
import csv
import math
import os
import tomllib

import pytest

from rollerpy import inprocess
from rollerpy.paths import PROBLEMS
from rollerpy.plots import rcf_map

SCENE = os.path.join(PROBLEMS, "wheel_rail_r260.toml")
FATIGUE = {"dang_van_a": 0.3, "dang_van_limit": 300.0, "shear_fatigue_limit": 300.0}


def test_johnsons_limits_and_the_initiation_lines():
    rows = rcf_map.rcf_rows([0.0, 0.5], 0.3, 161.7, FATIGUE, inprocess._roller.fatigue_of_cycle)
    free, sliding = rows
    assert abs(free["first_yield"] - 1.0 / 0.3007) < 0.01   # the largest in-plane shear 0.30 p0 at 0.78a
    assert abs(free["shakedown"] - 4.0) < 0.01
    assert abs(free["plastic_shakedown"] - 4.0) < 0.01
    assert math.isinf(free["surface"])
    for key in ("first_yield", "shakedown", "plastic_shakedown", "surface"):
        assert abs(sliding[key] - 2.0) < 0.01, key
    # The unit cycle's indices are the run's criteria: twice the stress, twice the value.
    cycle = next(rcf_map.unit_cycles(0.2, 0.3))
    once = inprocess._roller.fatigue_of_cycle(cycle, 0.3)
    twice = inprocess._roller.fatigue_of_cycle(2.0 * cycle, 0.3)
    assert abs(twice["dang_van"] - 2.0 * once["dang_van"]) < 1e-9 * abs(once["dang_van"])
    assert abs(twice["fi_sub"] - 2.0 * once["fi_sub"]) < 1e-9 * abs(once["fi_sub"])
    doubled = rcf_map.rcf_rows([0.0], 0.3, 161.7, dict(FATIGUE, shear_fatigue_limit=600.0),
                               inprocess._roller.fatigue_of_cycle)[0]
    assert abs(doubled["fi_sub_limit"] - 2.0 * free["fi_sub_limit"]) < 1e-9 * free["fi_sub_limit"]
    assert doubled["dang_van_limit"] == free["dang_van_limit"]
    # Friction raises the subsurface indices: the limits fall.
    assert sliding["fi_sub_limit"] < free["fi_sub_limit"] and sliding["dang_van_limit"] < free["dang_van_limit"]


def test_the_scene_point_and_the_files(tmp_path, capsys):
    resolved = tomllib.loads(inprocess.load_scene(SCENE).toml())
    k, nu, fatigue, point = rcf_map.scene_values(resolved)
    assert abs(k - 280.0 / math.sqrt(3.0)) < 1e-9       # the softened yield stress 320 - 40
    # The elastic wheel's two-body Hertz p0; its creep's traction only a run finds (--run marks it).
    assert abs(point[0] - 1408.55 / k) < 0.01 and point[1] == 0.0
    assert fatigue["shear_fatigue_limit"] == 300.0
    out = str(tmp_path / "map")
    assert rcf_map.main([SCENE, "--out", out, "--mu-max", "0.1", "--mu-step", "0.1"]) == 0
    with open(os.path.join(out, rcf_map.CSV)) as f:
        rows = list(csv.DictReader(f))
    assert [float(r["mu"]) for r in rows] == [0.0, 0.1]
    assert os.path.getsize(os.path.join(out, rcf_map.PNG)) > 10000
    # --set reaches the scene's keys as roller run's does: a scene without [fatigue] gets one.
    tutorial = os.path.join(PROBLEMS, "..", "docs", "tutorial", "my_burnishing.toml")
    sets = ["fatigue.dang_van_a=0.3", "fatigue.dang_van_limit=300.0", "fatigue.shear_fatigue_limit=300.0",
            "fatigue.critical_shear_strain=11.0"]
    assert rcf_map.main([tutorial, "--out", out, "--mu-max", "0.1", "--mu-step", "0.1"]
                        + [a for s in sets for a in ("--set", s)]) == 0
    with pytest.raises(SystemExit, match=r"no \[fatigue\] section"):
        rcf_map.main([tutorial, "--out", out])
    # --run marks the load a run measured: its summary.json's fatigue block.
    run = tmp_path / "run"
    run.mkdir()
    (run / "summary.json").write_text('{"fatigue": {"peak_pressure": 692.82, "shear_yield": 173.2, '
                                      '"traction_coefficient": 0.08}}')
    assert rcf_map.main([tutorial, "--out", out, "--mu-max", "0.1", "--mu-step", "0.1", "--run", str(run)]
                        + [a for s in sets for a in ("--set", s)]) == 0
    assert "p0/k = 4 at mu = 0.08" in capsys.readouterr().out
    row = {"first_yield": 3.3, "shakedown": 4.0, "plastic_shakedown": 4.0, "surface": math.inf}
    assert rcf_map.region(4.02, 0.0, row) == "ratchetting (within 1 % of the boundary at p0/k = 4)"
    assert rcf_map.region(3.7, 0.0, row) == "elastic shakedown"
