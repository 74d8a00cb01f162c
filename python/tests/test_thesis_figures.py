"""docs/thesis-figures.md against `rollerpy thesis-figures`: the page shows exactly the figures
the command copies, and the command block of docs/figures.md runs from a scratch folder and draws
every one of them."""
import os
import re
import subprocess

from conftest import LAUNCHER

from rollerpy.paths import ROOT
from rollerpy.validation.thesis_figures import FIGURES


def test_the_page_shows_every_figure_the_command_draws():
    page = open(os.path.join(ROOT, "docs", "thesis-figures.md")).read()
    shown = set(re.findall(r"\(img/thesis_([0-9a-z_]+)\.png\)", page))
    assert shown == set(FIGURES), "page only: %s; command only: %s" % (
        sorted(shown - set(FIGURES)), sorted(set(FIGURES) - shown))
    missing = [n for n in shown if not os.path.exists(os.path.join(ROOT, "docs", "img", "thesis_%s.png" % n))]
    assert not missing, "docs/img lacks: %s" % missing


def test_the_block_runs_and_draws_every_figure(roller, tmp_path):
    r = subprocess.run([LAUNCHER, "thesis-figures", "--roller", roller, "--work", str(tmp_path), "--no-copy"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    assert "%d figures drawn" % len(FIGURES) in r.stdout
