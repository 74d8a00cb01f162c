"""Nothing lost, nothing outside, the same answer twice (docs/stability.md, "Reliability").

test_environment: an output folder that cannot be used (in /proc, under a file, a name too long, on
  a read-only file system) ends with exit 2 and names the path; a disk that fills up while a run
  writes (a small tmpfs in a private mount namespace, `unshare -rm`, at many sizes) ends with exit
  3 or 0, never another code, with summary.json saying so; an Ipopt option naming a file is refused
  and the file is untouched; a memory cap far below the need ends with exit 3 and a summary.json.
test_repeat: a multi-pass scene run twice gives byte-identical outputs (the timing columns aside).
test_kill_resume: runs of a multi-pass, a dynamic and a frictional scene killed with SIGKILL at
  random moments (--kills per scene, --seed) and resumed (--resume) leave every file of the
  uninterrupted run, byte-identical.
The first failure raises with what differed.
"""
import os
import random
import shutil
import signal
import subprocess
import tempfile
import time

import pytest

from rollerpy.outputs import read_summary
from rollerpy.paths import PROBLEMS
from rollerpy.runner import run as run_logged
# Columns and keys that hold the machine's timing, not the computation's results.
TIMING_COLUMNS = {"solver.csv": {"wall_s", "ipopt_time_s"}}
# A resumed run factorises an elastic strip's tangent once afresh, where the uninterrupted run
# reused the factors it held (docs/scenes.md, state files): work, not results.
RESUME_COLUMNS = {"solver.csv": {"wall_s", "ipopt_time_s", "factorizations"}}
TIMING_KEYS = {"wall_s", "peak_memory_mb", "first_step", "resumed"}


def scene(name):
    return os.path.join(PROBLEMS, name + ".toml")


def run(roller, args, timeout=600, prefix=()):
    """roller ARGS (behind a prefix such as prlimit): (exit code, output); a timeout fails the test."""
    fd, log = tempfile.mkstemp(suffix=".log")
    os.close(fd)
    try:
        result = run_logged(list(prefix) + [roller] + args, log, timeout)
        assert not result.timed_out, "roller %s: no result within %d s" % (" ".join(args), timeout)
        return result.exit_code, result.output()
    finally:
        os.remove(log)


def without_columns(path, columns):
    with open(path) as f:
        rows = [line.rstrip("\n").split(",") for line in f]
    drop = {i for i, name in enumerate(rows[0]) if name in columns[os.path.basename(path)]}
    return [[c for i, c in enumerate(row) if i not in drop] for row in rows]


def same_outputs(reference, other, columns=TIMING_COLUMNS):
    """Every file of `reference` is in `other` with the same bytes (`columns` and the timing keys
    aside); returns the differences."""
    problems = []
    for name in sorted(os.listdir(reference)):
        a, b = os.path.join(reference, name), os.path.join(other, name)
        if not os.path.exists(b):
            problems.append("%s: missing" % name)
        elif name in columns:
            if without_columns(a, columns) != without_columns(b, columns):
                problems.append("%s: rows differ" % name)
        elif name == "summary.json":
            sa, sb = read_summary(reference), read_summary(other)
            for key in set(sa) | set(sb):
                if key not in TIMING_KEYS and sa.get(key) != sb.get(key):
                    problems.append("summary.json: %s = %r, expected %r" % (key, sb.get(key), sa.get(key)))
        else:
            with open(a, "rb") as fa, open(b, "rb") as fb:
                if fa.read() != fb.read():
                    problems.append("%s: bytes differ" % name)
    return problems


# ---- environment failures -----------------------------------------------------------------

def check_unusable_folders(roller, tmp):
    a_file = os.path.join(tmp, "a_file")
    with open(a_file, "w") as f:
        f.write("x\n")
    for out in ["/proc/roller_out", os.path.join(a_file, "out"), os.path.join(tmp, "n" * 300)]:
        rc, text = run(roller, ["run", scene("block_compression"), "--steps", "1", "--out", out])
        assert rc == 2, "--out %s: exit %d, expected 2\n%s" % (out[:60], rc, text)
        assert "roller: input error:" in text and out[:40] in text, text
    print("unusable folders: exit 2 naming the path (/proc, under a file, a 300-character name)")


def in_namespace(script):
    """Runs a shell script as root of a private user and mount namespace (its mounts vanish with
    it); returns (exit code, output)."""
    r = subprocess.run(["unshare", "-rm", "sh", "-c", script], capture_output=True, text=True, timeout=600)
    assert "unshare failed" not in r.stderr, "unshare -rm is needed for the file-system checks: " + r.stderr
    return r.returncode, r.stdout + r.stderr


def check_read_only(roller, tmp):
    mnt = os.path.join(tmp, "ro")
    os.makedirs(mnt)
    rc_file = os.path.join(tmp, "ro_rc")
    # A folder that exists on a file system mounted read-only, and one to be created there.
    script = ("mount -t tmpfs -o size=1m none {m} && mkdir {m}/out && mount -o remount,ro {m} && "
              "{r} run {s} --steps 1 --out {m}/out; echo $? > {rc}; "
              "{r} run {s} --steps 1 --out {m}/new; echo $? >> {rc}").format(
                  m=mnt, r=roller, s=scene("block_compression"), rc=rc_file)
    _, text = in_namespace(script)
    with open(rc_file) as f:
        codes = [int(line) for line in f]
    assert codes == [2, 2], "read-only file system: exit codes %s, expected [2, 2]\n%s" % (codes, text)
    assert "Read-only file system" in text and mnt in text, text
    print("read-only file system: exit 2 naming the path (an existing folder and a new one)")


def check_full_disk(roller, tmp):
    """A disk that fills up at some point of the run, at many sizes: exit 3 (or 0 when all fits),
    and a summary.json that says so; the fields of the steps done complete."""
    seen, failed_files = {}, set()
    for size_kib in list(range(24, 208, 4)) + [400, 600]:
        mnt, keep = os.path.join(tmp, "full%d" % size_kib), os.path.join(tmp, "kept%d" % size_kib)
        os.makedirs(mnt)
        script = ("mount -t tmpfs -o size={k}k none {m} && {r} run {s} --steps 4 --out {m}/out; echo $? > {m}.rc; "
                  "cp -r {m}/out {keep} 2>/dev/null; true").format(k=size_kib, m=mnt, r=roller,
                                                                   s=scene("block_compression"), keep=keep)
        _, text = in_namespace(script)
        with open(mnt + ".rc") as f:
            rc = int(f.read())
        assert rc in (0, 3), "tmpfs of %d KiB: exit %d, expected 3 (disk full) or 0\n%s" % (size_kib, rc, text)
        if rc == 3:
            assert "roller: system error:" in text and "No space left on device" in text and mnt in text, text
            failed_files.add(text.split(mnt + "/out/")[1].split("'")[0].split(":")[0].split(".")[-1])
        if os.path.exists(os.path.join(keep, "scene.resolved.toml")):
            summary = read_summary(keep)  # parses: never empty, never cut
            assert summary["exit_code"] == rc, "tmpfs of %d KiB: summary.json %s, exit %d" % (size_kib, summary, rc)
            assert summary["status"] == ("completed" if rc == 0 else "system_error"), summary
            for name in os.listdir(keep):
                assert not name.endswith(".tmp"), "a temporary file left behind: " + name
        seen[rc] = seen.get(rc, 0) + 1
    assert seen.get(3, 0) >= 4, "too few sizes filled the disk: %s" % seen
    assert {"csv", "vtu", "cbor"} <= failed_files, "the disk filled up only at %s" % failed_files
    print("full disk at %d sizes: exit codes %s (failing at %s files), summary.json parsed with the same code "
          "each time" % (sum(seen.values()), seen, sorted(failed_files)))


def check_ipopt_file_options(roller, tmp):
    victim = os.path.join(tmp, "victim.txt")
    with open(victim, "w") as f:
        f.write("keep me\n")
    for key in ["output_file", "option_file_name", "hsllib"]:
        rc, text = run(roller, ["run", scene("hertz"), "--steps", "1", "--out", os.path.join(tmp, "ip_" + key),
                                "--set", 'contact.ipopt.options.%s="%s"' % (key, victim)])
        assert rc == 2 and key in text and "naming a file or a library" in text, text
    with open(victim) as f:
        assert f.read() == "keep me\n", "the file named by an Ipopt option was changed"
    print("Ipopt options naming files: refused (exit 2), the file untouched")


def check_memory_cap(roller, tmp):
    out = os.path.join(tmp, "capped")
    cap = 300 * 1024 * 1024  # the run needs about 0.7 GiB of address space
    rc, text = run(roller, ["run", scene("block_compression"), "--refine", "24", "--steps", "1", "--out", out],
                   timeout=120, prefix=["prlimit", "--as=%d" % cap, "--"])
    assert rc == 3, "memory cap: exit %d, expected 3\n%s" % (rc, text)
    assert "GiB" in text and "out_of_core = true" in text and "ulimit -v" in text, text
    summary = read_summary(out)
    assert summary["status"] == "system_error" and summary["exit_code"] == 3, summary
    print("memory cap of 300 MiB: exit 3 naming the memory needed and the fixes, summary.json written")


# ---- the same answer twice ------------------------------------------------------------------

def check_repeat(roller, tmp):
    # Two passes of the shakedown strip (1.8e4 free dofs): its factorisations without a Schur
    # complement are ordered by SCOTCH (solver/mumps_factorization.cpp), which parted two runs at
    # the first one, in pass 2, before it ran on one thread.
    args = ["run", scene("shakedown_p45"), "--set", "passes.count=2", "--set", "output.every=7"]
    first, second = os.path.join(tmp, "first"), os.path.join(tmp, "second")
    for out in (first, second):
        rc, text = run(roller, args + ["--out", out], timeout=1200)
        assert rc == 0, text
    problems = same_outputs(first, second)
    assert not problems, "two runs of one scene differ: " + "; ".join(problems)
    print("two runs of shakedown_p45 (2 passes): %d files byte-identical (timing aside)" % len(os.listdir(first)))


# ---- kill -9 and --resume -------------------------------------------------------------------

KILL_SCENES = [  # (scene, arguments): a multi-pass, a dynamic, a frictional one, 2-9 s each
    ("burnishing", ["--set", "passes.count=2"]),
    ("z4_v25", ["--refine", "4"]),
    ("cattaneo_mindlin", ["--refine", "3"]),
]


def check_kill_resume(roller, tmp, kills, rng):
    done = 0
    for name, extra in KILL_SCENES:
        reference = os.path.join(tmp, name + "_whole")
        t0 = time.time()
        rc, text = run(roller, ["run", scene(name), "--out", reference] + extra)
        assert rc == 0, text
        duration = time.time() - t0
        for k in range(kills):
            out = os.path.join(tmp, "%s_killed%d" % (name, k))
            proc = subprocess.Popen([roller, "run", scene(name), "--out", out] + extra,
                                    stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            when = rng.uniform(0.05, 0.95) * duration
            time.sleep(when)
            proc.send_signal(signal.SIGKILL)
            proc.wait()
            if os.path.exists(os.path.join(out, "checkpoint.cbor")):
                rc, text = run(roller, ["run", scene(name), "--out", out, "--resume"] + extra)
            else:  # killed before the first checkpoint: a fresh run into the same folder
                rc, text = run(roller, ["run", scene(name), "--out", out] + extra)
            assert rc == 0, text
            problems = same_outputs(reference, out, RESUME_COLUMNS)
            assert not problems, "%s (a %.2f s run) killed at %.2f s and resumed: %s" % (
                name, duration, when, "; ".join(problems))
            shutil.rmtree(out)
            done += 1
        print("%s: %d kills at random moments, each resumed to the uninterrupted run's files" % (name, kills))
    return done


@pytest.fixture
def tmp(tmp_path):
    return str(tmp_path)


def test_environment(roller, tmp):
    check_unusable_folders(roller, tmp)
    check_read_only(roller, tmp)
    check_full_disk(roller, tmp)
    check_ipopt_file_options(roller, tmp)
    check_memory_cap(roller, tmp)


def test_repeat(roller, tmp):
    check_repeat(roller, tmp)


def test_kill_resume(roller, tmp, request):
    kills = request.config.getoption("--kills")
    assert check_kill_resume(roller, tmp, kills, random.Random(request.config.getoption("--seed"))) == 3 * kills
