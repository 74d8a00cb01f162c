"""The shakedown map in one command (docs/validation.md, "Shakedown map"): runs the study
problems/studies/shakedown_map.toml on the study runner (`rollerpy study`: a Dask LocalCluster
of --jobs workers, or --scheduler) and draws the map (`rollerpy plot-shakedown-map`) with Melan's
bound of the study's strip beside Johnson's (`roller shakedown-limit`, --melan).

usage: ./rollerpy shakedown-map [--out out/studies/shakedown_map] [--jobs N]
                               [--scheduler tcp://HOST:8786] [--resume]
                               [--roller build/roller] [--study FILE] [--melan SCENE]
"""
import os

from ..command import parser
from ..paths import DEFAULT_ROLLER, PROBLEMS, ROOT
from ..plots import shakedown_map as plot_map
from ..study import cli as study


def main(argv=None):
    ap = parser("shakedown-map", __doc__)
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "studies", "shakedown_map"))
    ap.add_argument("--jobs", type=int, default=os.cpu_count())
    ap.add_argument("--scheduler")
    ap.add_argument("--resume", action="store_true")
    ap.add_argument("--roller", default=DEFAULT_ROLLER)
    ap.add_argument("--study", default=os.path.join(PROBLEMS, "studies", "shakedown_map.toml"))
    ap.add_argument("--melan", default=os.path.join(PROBLEMS, "shakedown_p45.toml"),
                    help="the scene whose Melan line the map draws (the study's strip)")
    args = ap.parse_args(argv)
    options = [args.study, "--out", args.out, "--jobs", str(args.jobs), "--roller", args.roller]
    options += ["--scheduler", args.scheduler] if args.scheduler else []
    options += ["--resume"] if args.resume else []
    rc = study.main(options)
    if rc != 0:
        return rc
    return plot_map.main([os.path.join(args.out, "study.csv"), "--melan", args.melan, "--roller", args.roller])
