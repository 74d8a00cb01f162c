#!/usr/bin/python3
"""The shakedown map in one command (docs/validation.md, "Shakedown map"): runs the study
problems/studies/shakedown_map.toml on the study runner (scripts/study.py: a Dask LocalCluster
of --jobs workers, or --scheduler) and draws the map (scripts/plot_shakedown_map.py).

usage: /usr/bin/python3 scripts/shakedown_map.py [--out out/studies/shakedown_map] [--jobs N]
                                                 [--scheduler tcp://HOST:8786] [--resume]
                                                 [--roller build/roller] [--study FILE]
"""
import argparse
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "studies", "shakedown_map"))
    ap.add_argument("--jobs", type=int, default=os.cpu_count())
    ap.add_argument("--scheduler")
    ap.add_argument("--resume", action="store_true")
    ap.add_argument("--roller", default=os.path.join(ROOT, "build", "roller"))
    ap.add_argument("--study", default=os.path.join(ROOT, "problems", "studies", "shakedown_map.toml"))
    args = ap.parse_args()
    cmd = ["/usr/bin/python3", os.path.join(ROOT, "scripts", "study.py"), args.study, "--out", args.out,
           "--jobs", str(args.jobs), "--roller", args.roller]
    cmd += ["--scheduler", args.scheduler] if args.scheduler else []
    cmd += ["--resume"] if args.resume else []
    rc = subprocess.run(cmd).returncode
    if rc != 0:
        return rc
    return subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts", "plot_shakedown_map.py"),
                           os.path.join(args.out, "study.csv")]).returncode


if __name__ == "__main__":
    sys.exit(main())
