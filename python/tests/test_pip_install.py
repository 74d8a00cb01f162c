"""The documented install (docs/python.md, "Installing rollerpy"): pip installs rollerpy from the
checkout into a virtual environment with Debian's packages visible, building the native module and
the roller program with CMake (python/setup.py; here from the test's own build folder, so that pip
only links and copies). From another folder and without PYTHONPATH, `import rollerpy` then finds
the compiled module, `run` is in dir(), a run completes, and the console command and the program
work."""
import os
import subprocess

import pytest

from rollerpy.paths import PROBLEMS, ROOT

CHECK = """
import os, sys
import rollerpy
assert "run" in dir(rollerpy), dir(rollerpy)
run = rollerpy.run(sys.argv[1], set={"steps.count": 1, "roller.path[0].steps": [1, 1]})
assert run.status == "completed", run.message
from rollerpy import _roller, paths
print(os.path.dirname(rollerpy.__file__), _roller.__file__, paths.DEFAULT_ROLLER, run.roller["fy"][-1])
"""


def test_pip_install_into_a_venv_gives_a_working_run(tmp_path):
    venv = tmp_path / "venv"
    subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python = str(venv / "bin" / "python")
    env = dict(os.environ)
    env.pop("PYTHONPATH", None)
    build = os.environ.get("ROLLER_BUILD_DIR")
    assert build, "CTest gives its build folder in ROLLER_BUILD_DIR"
    # pip's build must find nothing to do: one that relinked roller would pull it from under the
    # tests running beside this one (a dry run of Ninja stops at its own re-check of the globs).
    newest = max(os.path.getmtime(os.path.join(folder, name)) for top in ("src", "include")
                 for folder, _, names in os.walk(os.path.join(ROOT, top)) for name in names)
    if newest > os.path.getmtime(os.path.join(build, "roller")):
        pytest.fail("%s is older than the sources: build it first (scripts/build.sh)" % build, pytrace=False)
    source_files = set(os.listdir(os.path.join(ROOT, "python")))
    pip = subprocess.run([python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--quiet",
                          os.path.join(ROOT, "python")], env=env, capture_output=True, text=True, timeout=1200)
    assert pip.returncode == 0, pip.stdout + pip.stderr
    # The build's own files stay in the build folder, not beside the sources.
    assert set(os.listdir(os.path.join(ROOT, "python"))) == source_files
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    done = subprocess.run([python, "-c", CHECK, os.path.join(PROBLEMS, "hertz.toml")], cwd=elsewhere, env=env,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    package, module, program, fy = done.stdout.split()
    assert package.startswith(str(venv)) and module.startswith(str(venv)) and program.startswith(str(venv))
    assert float(fy) > 0.0
    assert subprocess.run([program, "--version"], capture_output=True, text=True).stdout.startswith("roller")
    command = subprocess.run([str(venv / "bin" / "rollerpy"), "--help"], cwd=elsewhere, env=env,
                             capture_output=True, text=True)
    assert command.returncode == 0 and "plot-scene" in command.stdout
