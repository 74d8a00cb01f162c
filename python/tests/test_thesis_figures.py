#!/usr/bin/python3
"""docs/thesis-figures.md against scripts/thesis_figures.py: the page shows exactly the figures
the script copies, and the command block of docs/figures.md runs from a scratch folder and draws
every one of them.

usage: test_thesis_figures.py ROLLER
"""
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from thesis_figures import FIGURES  # noqa: E402


def test_the_page_shows_every_figure_the_script_draws():
    page = open(os.path.join(ROOT, "docs", "thesis-figures.md")).read()
    shown = set(re.findall(r"\(img/thesis_([0-9a-z_]+)\.png\)", page))
    assert shown == set(FIGURES), "page only: %s; script only: %s" % (
        sorted(shown - set(FIGURES)), sorted(set(FIGURES) - shown))
    missing = [n for n in shown if not os.path.exists(os.path.join(ROOT, "docs", "img", "thesis_%s.png" % n))]
    assert not missing, "docs/img lacks: %s" % missing


def test_the_block_runs_and_draws_every_figure(roller):
    work = tempfile.mkdtemp()
    r = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts", "thesis_figures.py"), "--roller", roller,
                        "--work", work, "--no-copy"], capture_output=True, text=True)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    assert "%d figures drawn" % len(FIGURES) in r.stdout


if __name__ == "__main__":
    test_the_page_shows_every_figure_the_script_draws()
    print("ok: the page shows every figure")
    test_the_block_runs_and_draws_every_figure(sys.argv[1])
    print("ok: the block draws every figure")
