#!/usr/bin/python3
"""Mutation fuzzer for scene files and --set values (docs/stability.md, "Hostile input").

usage: /usr/bin/python3 scripts/fuzz_scenes.py [--cases 200] [--seed 1] [--roller ./build/roller]
                                               [--out out/fuzz] [--timeout 30] [--steps 2]

Each case takes a shipped scene (problems/*.toml), mutates it (a line deleted or duplicated, a
value replaced by nan/inf/huge/tiny/negative/wrong-typed ones, the file truncated, binary garbage
inserted, deeply nested dotted keys, or a --set override of a random key with such a value) and
runs `roller run` on it for a few steps under a timeout. A case passes when roller ends with a
documented exit code (0 converged, 1 a step failed with an "error:" line, 2 input error with
"input error", 3 a system error such as a full disk) and no output file holds nan or inf. It
fails on a crash (signal), a timeout (hang), an internal error (exit 4, "roller: internal
error:"), an undocumented exit code, or nan/inf in an
output. Every failing case leaves its reproducer in OUT/failures/<n>/ (scene.toml, command.txt,
output.txt). Exit code 0 when every case passed, 1 otherwise. The CTest "fuzz" label runs a short
fixed-seed variant; a long run for a night: --cases 10000 --seed $RANDOM.
"""
import argparse
import glob
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Scenes that run on their own (z3_data02 needs z3_data01's final state); small ones weigh more.
SEEDS = ["block_compression", "hertz", "cattaneo", "bar_impact", "z1_outf05", "z2_infini", "z2_large",
         "z4_v25", "stability_thin", "rolling_friction", "hertz_nu049", "block_compression", "hertz",
         "cattaneo_mindlin", "burnishing"]
HOSTILE_NUMBERS = ["nan", "inf", "-inf", "0", "-0.0", "-1", "1e308", "-1e308", "1e-308", "1e-300", "1e300",
                   "4294967297", "9007199254740993", "-4294967298", "2147483648", "1e20", "0.5", "3"]
WRONG_TYPES = ['"x"', "true", "[]", "{}", "[1, 2, 3]", '""', "{ value = nan }", "[nan, 0.0]"]
NUMBER = re.compile(r"^(\s*[A-Za-z_][A-Za-z0-9_]*\s*=\s*)(.+?)(\s*#.*)?$")


def mutate_text(text, rng):
    lines = text.split("\n")
    kind = rng.choice(["value", "value", "value", "type", "delete", "duplicate", "truncate", "garbage", "nest"])
    assignments = [i for i, l in enumerate(lines) if NUMBER.match(l) and not l.lstrip().startswith("#")]
    if kind in ("value", "type") and assignments:
        i = rng.choice(assignments)
        m = NUMBER.match(lines[i])
        new = rng.choice(HOSTILE_NUMBERS if kind == "value" else WRONG_TYPES)
        old = m.group(2)
        # Inside arrays and inline tables replace one number, else the whole value.
        numbers = list(re.finditer(r"-?\d+(\.\d*)?([eE][-+]?\d+)?", old))
        if numbers and (old.startswith("[") or old.startswith("{")):
            n = rng.choice(numbers)
            old = old[:n.start()] + new + old[n.end():]
        else:
            old = new
        lines[i] = m.group(1) + old
        return "\n".join(lines), "%s at line %d" % (kind, i + 1)
    if kind == "delete" and lines:
        i = rng.randrange(len(lines))
        del lines[i]
        return "\n".join(lines), "line %d deleted" % (i + 1)
    if kind == "duplicate" and lines:
        i = rng.randrange(len(lines))
        lines.insert(i, lines[i])
        return "\n".join(lines), "line %d duplicated" % (i + 1)
    if kind == "truncate":
        n = rng.randrange(len(text) + 1)
        return text[:n], "truncated at byte %d" % n
    if kind == "garbage":
        n = rng.randrange(len(text) + 1)
        junk = "".join(chr(rng.randrange(1, 256)) for _ in range(rng.randrange(1, 40)))
        return text[:n] + junk + text[n:], "garbage at byte %d" % n
    depth = rng.choice([2, 50, 1000, 5000])
    return ".".join(["a"] * depth) + ".b = 1\n" + text, "%d nested dotted keys" % depth


def set_override(keys, rng):
    key = rng.choice(keys)
    value = rng.choice(HOSTILE_NUMBERS + WRONG_TYPES)
    return ["--set", "%s=%s" % (key, value)], "--set %s=%s" % (key, value)


def scene_keys(roller):
    out = subprocess.run([roller, "scene-keys"], capture_output=True, text=True, check=True).stdout
    keys = []
    for line in out.splitlines()[1:]:
        k = line.split()[0] if line.split() else ""
        if k and "[]" not in k and "." in k:
            keys.append(k)
    return keys


def nonfinite_outputs(out_dir):
    bad = []
    for path in glob.glob(os.path.join(out_dir, "*")):
        if not path.endswith((".csv", ".json", ".pvd", ".toml")):
            continue
        with open(path, errors="replace") as f:
            text = f.read()
        if re.search(r"(?<![A-Za-z_])(nan|inf|NaN|Inf|null)(?![A-Za-z_])", text):
            bad.append(os.path.basename(path))
    return bad


def run_case(roller, scene_path, extra, out_dir, timeout, steps):
    cmd = [roller, "run", scene_path, "--out", out_dir, "--steps", str(steps), "--overwrite"] + extra
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        output, _ = p.communicate(timeout=timeout)
        return cmd, p.returncode, output.decode(errors="replace"), False
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        output, _ = p.communicate()
        return cmd, None, output.decode(errors="replace"), True


def verdict(rc, output, timed_out, out_dir):
    if timed_out:
        return "hang (timeout)"
    if rc is None or rc < 0 or rc >= 128:
        return "crash (signal %s)" % (-rc if rc is not None and rc < 0 else rc)
    if "roller: internal error:" in output or "roller: error:" in output:
        tail = output.split("error:", 1)[-1].strip().splitlines()
        return "unexpected exception: " + (tail[0][:120] if tail else "")
    if rc == 2 and "input error" not in output and "Run with --help" not in output:
        return "exit 2 without an input-error message"
    if rc == 1 and "error:" not in output:
        return "exit 1 without an error line"
    if rc == 3 and "system error" not in output:
        return "exit 3 without a system-error message"
    if rc not in (0, 1, 2, 3):
        return "undocumented exit code %d" % rc
    bad = nonfinite_outputs(out_dir)
    if bad:
        return "nan/inf in " + ", ".join(bad)
    return ""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--roller", default=os.path.join(ROOT, "build", "roller"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "fuzz"))
    ap.add_argument("--timeout", type=float, default=30.0)
    ap.add_argument("--steps", type=int, default=2)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    keys = scene_keys(args.roller)
    work = os.path.join(args.out, "work")
    failures = os.path.join(args.out, "failures")
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(work)
    counts = {}
    n_failed = 0
    t0 = time.monotonic()
    for case in range(1, args.cases + 1):
        seed = rng.choice(SEEDS)
        with open(os.path.join(ROOT, "problems", seed + ".toml")) as f:
            text = f.read()
        extra, what = [], ""
        if rng.random() < 0.3:
            extra, what = set_override(keys, rng)
        else:
            text, what = mutate_text(text, rng)
        scene_path = os.path.join(work, "case.toml")
        with open(scene_path, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(text)
        out_dir = os.path.join(work, "out")
        cmd, rc, output, timed_out = run_case(args.roller, scene_path, extra, out_dir, args.timeout, args.steps)
        problem = verdict(rc, output, timed_out, out_dir)
        key = "timeout" if timed_out else str(rc)
        counts[key] = counts.get(key, 0) + 1
        if problem:
            n_failed += 1
            d = os.path.join(failures, "%04d" % case)
            os.makedirs(d)
            shutil.copy(scene_path, os.path.join(d, "scene.toml"))
            with open(os.path.join(d, "command.txt"), "w") as f:
                f.write("# %s: %s (from problems/%s.toml)\n%s\n" % (problem, what, seed, " ".join(cmd)))
            with open(os.path.join(d, "output.txt"), "w") as f:
                f.write(output)
            print("case %4d FAILED %s: %s (problems/%s.toml) -> %s" % (case, problem, what, seed, d), flush=True)
        shutil.rmtree(out_dir, ignore_errors=True)
    print("fuzz: %d cases in %.0f s (seed %d), exit codes %s; %d failed" % (
        args.cases, time.monotonic() - t0, args.seed,
        ", ".join("%s: %d" % kv for kv in sorted(counts.items())), n_failed))
    return 1 if n_failed else 0


if __name__ == "__main__":
    sys.exit(main())
