"""The roller binary for the tests that run it: --roller PATH (CTest passes its build's) or the
environment variable ROLLER; a test that needs it fails without it (it must never pass empty)."""
import os

import pytest

from rollerpy.paths import PROBLEMS, ROOT
from rollerpy.runner import roller_command, run

LAUNCHER = os.path.join(ROOT, "rollerpy")  # ./rollerpy: the commands as a user runs them


def pytest_addoption(parser):
    parser.addoption("--roller", default=os.environ.get("ROLLER"), help="the roller binary (default: $ROLLER)")
    parser.addoption("--kills", type=int, default=4, help="test_reliability: kills per scene (3 scenes)")
    parser.addoption("--seed", type=int, default=1, help="test_reliability: the seed of the kill moments")


@pytest.fixture(scope="session")
def roller(request):
    path = request.config.getoption("--roller")
    if not path or not os.access(path, os.X_OK):
        pytest.fail("no roller binary: give --roller PATH or ROLLER=PATH (got %r)" % path, pytrace=False)
    return os.path.abspath(path)


def run_scene(roller, name, folder):
    """problems/NAME.toml run into folder/NAME; returns the output folder. Fails the caller's set-up
    with roller's output when the run does not converge."""
    out = os.path.join(folder, name)
    run(roller_command(roller, os.path.join(PROBLEMS, name + ".toml"), out), out + ".log").check()
    return out


@pytest.fixture(scope="session")
def cattaneo_out(roller, tmp_path_factory):
    """Cattaneo at its default mesh: small kinematics, friction (stick and slip nodes), 8 steps."""
    return run_scene(roller, "cattaneo", str(tmp_path_factory.mktemp("scenes")))
