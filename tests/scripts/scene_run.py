"""One shipped scene run into a fresh temporary folder, for the script tests that read a run's
output (test_vtu_fields.py, test_plot_scene.py)."""
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run_scene(roller, name):
    """Runs problems/NAME.toml with `roller`; returns its output folder. Fails the caller's set-up
    with roller's output when the run does not converge."""
    out = os.path.join(tempfile.mkdtemp(), name)
    r = subprocess.run([roller, "run", os.path.join(ROOT, "problems", name + ".toml"), "--out", out],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    return out
