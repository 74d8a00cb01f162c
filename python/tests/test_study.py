#!/usr/bin/python3
"""The study runner (scripts/study.py, docs/studies.md): a 2 x 2 study on a LocalCluster with two
workers gives the same study.csv values as the points run serially; failing points (bad input,
the study's timeout) are recorded and the others complete; a study killed after some points and
rerun with --resume runs only the missing points; the study-file loader rejects unknown keys and
bad ranges with the file, the key and what was expected.

usage: /usr/bin/python3 tests/scripts/test_study.py ROLLER_EXE   (CTest passes build/roller)
"""
import csv
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from roller_study.study_file import StudyError, load  # noqa: E402

ROLLER = None
STUDY = [sys.executable, os.path.join(ROOT, "scripts", "study.py")]
BLOCK = os.path.join(ROOT, "problems", "block_compression.toml")


def write(directory, name, text):
    path = os.path.join(directory, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def roller_processes_in(out):
    """Pids of the live processes whose command line names `out`."""
    pids = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                if out.encode() in f.read():
                    with open("/proc/%s/stat" % pid) as s:
                        if s.read().rsplit(")", 1)[1].split()[0] != "Z":
                            pids.append(int(pid))
        except OSError:
            pass
    return pids


def run_study(*args):
    return subprocess.run(STUDY + list(args) + ["--roller", ROLLER, "--quiet"], capture_output=True, text=True)


TINY = """
scene = "%s"
collect = ["converged", "iterations_total", "solver.csv:residual", "solver.csv:iterations"]
[set]
"steps.count" = 2
[grid]
"material.E" = [1.0e5, 2.0e5]
"material.nu" = { start = 0.2, stop = 0.3, count = 2 }
""" % BLOCK


class Loader(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()

    def error(self, text):
        path = write(self.dir, "s.toml", text)
        with self.assertRaises(StudyError) as e:
            load(path)
        self.assertIn(path, str(e.exception))
        return str(e.exception)

    def test_a_grid_expands_to_every_combination(self):
        study = load(write(self.dir, "s.toml", TINY))
        self.assertEqual(len(study.points), 4)
        self.assertEqual(study.parameters, ["material.E", "material.nu"])
        self.assertEqual([p.values for p in study.points][1], {"material.E": 1.0e5, "material.nu": 0.3})

    def test_ranges(self):
        study = load(write(self.dir, "s.toml", TINY.replace("count = 2 }", "count = 3 }")))
        self.assertEqual(sorted({p.values["material.nu"] for p in study.points}), [0.2, 0.25, 0.3])
        study = load(write(self.dir, "s.toml", TINY.replace("count = 2 }", "step = 0.05 }")))
        self.assertEqual(len({p.values["material.nu"] for p in study.points}), 3)

    def test_unknown_keys_and_bad_ranges_are_rejected(self):
        self.assertIn("colect = ['converged', ", self.error(TINY.replace("collect", "colect")))
        self.assertIn("unknown key; expected one of backends, collect", self.error(TINY.replace("collect", "colect")))
        self.assertIn("grid.material.nu.count = 0: expected an integer 1 <= count",
                      self.error(TINY.replace("count = 2", "count = 0")))
        self.assertIn("grid.material.nu.step = -0.1: the step must go from start",
                      self.error(TINY.replace("count = 2", "step = -0.1")))
        self.assertIn("exactly one of count and step",
                      self.error(TINY.replace("count = 2", "count = 2, step = 0.1")))
        self.assertIn("grid.material.nu.stpo", self.error(TINY.replace("stop", "stpo")))
        self.assertIn("grid.material.E = []", self.error(TINY.replace("[1.0e5, 2.0e5]", "[]")))
        self.assertIn("backends = ['simplex']", self.error('backends = ["simplex"]\n' + TINY))
        self.assertIn("scene = 'nowhere.toml': no such file", self.error(TINY.replace(BLOCK, "nowhere.toml")))
        self.assertIn("either as [grid]", self.error(TINY + '[[point]]\n"material.E" = 1.0\n'))
        self.assertIn("set.material.E", self.error(TINY.replace('"steps.count" = 2', '"material.E" = 3.0')))
        self.assertIn("not valid TOML", self.error("scene = "))
        self.assertIn("collect = 'wall_s': study.csv has this column already",
                      self.error(TINY.replace('collect = ["converged"', 'collect = ["wall_s"')))


class Runner(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp()

    def test_local_cluster_gives_the_serial_values(self):
        study = write(self.dir, "tiny.toml", TINY)
        serial, dask = os.path.join(self.dir, "serial"), os.path.join(self.dir, "dask")
        r = run_study(study, "--out", serial, "--serial")
        self.assertEqual(r.returncode, 0, r.stderr)
        r = run_study(study, "--out", dask, "--jobs", "2")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("LocalCluster with 2 workers", r.stdout)
        a, b = rows(os.path.join(serial, "study.csv")), rows(os.path.join(dask, "study.csv"))
        self.assertEqual(len(a), 4)
        same = ["index", "backend", "material.E", "material.nu", "converged", "iterations_total",
                "solver.csv:residual", "solver.csv:iterations", "status"]
        self.assertEqual([[r[k] for k in same] for r in a], [[r[k] for k in same] for r in b])
        self.assertTrue(all(r["status"] == "ok" and r["converged"] == "True" for r in a))
        self.assertTrue(all(os.path.isdir(r["out"]) for r in b))

    def test_failing_points_are_recorded_and_the_others_complete(self):
        study = write(self.dir, "fail.toml", """
scene = "%s"
timeout = 10
collect = ["converged"]
[[point]]
"material.nu" = 0.7
"mesh.refine" = 1
"steps.count" = 2
[[point]]
"material.nu" = 0.3
"mesh.refine" = 1
"steps.count" = 2
[[point]]
"material.nu" = 0.3
"mesh.refine" = 10
"steps.count" = 1000
""" % BLOCK)
        # The timeout leaves the second point (0.2 s under the sanitizers) a wide margin when the
        # machine is loaded: with 2 s and a refine-40 mesh beside it, it once timed out in the
        # sanitized build under ctest -j2. The third point is long by its steps (0.5 s each in a
        # Release build), not by a mesh whose memory loads the machine.
        out = os.path.join(self.dir, "out")
        r = run_study(study, "--out", out, "--jobs", "2")
        self.assertEqual(r.returncode, 0, r.stderr)
        got = rows(os.path.join(out, "study.csv"))
        self.assertEqual([g["status"] for g in got], ["input_error", "ok", "timeout"])
        self.assertIn("material.nu", got[0]["message"])
        self.assertEqual(got[1]["converged"], "True")
        self.assertIn("no result within 10 s", got[2]["message"])

    def test_a_killed_study_resumes_with_the_missing_points_only(self):
        study = write(self.dir, "slow.toml", """
scene = "%s"
collect = ["converged", "iterations_total"]
[set]
"steps.count" = 2
"mesh.refine" = 6
[grid]
"material.E" = [1.0e5, 1.5e5, 2.0e5, 2.5e5]
""" % BLOCK)
        out = os.path.join(self.dir, "out")
        proc = subprocess.Popen(STUDY + [study, "--out", out, "--serial", "--quiet", "--roller", ROLLER],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        first = os.path.join(out, "points", "p000", "point.json")
        deadline = time.monotonic() + 120
        while not os.path.exists(first) and time.monotonic() < deadline:
            time.sleep(0.02)
        os.killpg(proc.pid, signal.SIGKILL)  # the study; the roller it runs has a session of its own
        proc.wait()
        self.assertTrue(os.path.exists(first))
        # The running point's roller dies with the study: an orphan would go on writing into the
        # folder the resumed study gives to the same point's new run.
        deadline = time.monotonic() + 0.25  # a point runs for about 0.6 s
        while roller_processes_in(out) and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertEqual(roller_processes_in(out), [])
        done = sorted(d for d in os.listdir(os.path.join(out, "points"))
                      if os.path.exists(os.path.join(out, "points", d, "point.json")))
        self.assertLess(len(done), 4)
        stamps = {d: os.path.getmtime(os.path.join(out, "points", d, "point.json")) for d in done}
        r = run_study(study, "--out", out, "--serial", "--resume")
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("4 points (%d complete, %d to run)" % (len(done), 4 - len(done)), r.stdout)
        for d, t in stamps.items():  # not run again
            self.assertEqual(os.path.getmtime(os.path.join(out, "points", d, "point.json")), t)
        got = rows(os.path.join(out, "study.csv"))
        self.assertEqual([g["status"] for g in got], ["ok"] * 4)
        self.assertEqual([g["index"] for g in got], ["0", "1", "2", "3"])


if __name__ == "__main__":
    ROLLER = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
