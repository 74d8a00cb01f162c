"""Draws every figure of the thesis's chapter 5: runs the command block of docs/figures.md (between
its `thesis-figures:begin` and `:end` markers) and copies one PNG per thesis figure to docs/img/,
where docs/thesis-figures.md shows them.

usage: ./rollerpy thesis-figures [--roller PATH] [--work DIR] [--no-copy]
  --roller  the roller binary the block's `./build/roller` stands for (default: build/roller)
  --work    the folder to run in (default: the repository; out/ is created there). Another folder
            gets a copy of problems/ and links to the launcher ./rollerpy and the binary, so a
            test can run the block in a scratch folder.
  --no-copy check that every figure was drawn, copy nothing.
The block is run by bash with `set -euo pipefail`: the first failing command stops it and this
script exits 1; a figure that was not drawn is named and exits 1 too.
"""
import os
import shutil
import subprocess
import sys

from ..command import parser
from ..paths import DEFAULT_ROLLER, ROOT

FIGURES_MD = os.path.join(ROOT, "docs", "figures.md")
IMG = os.path.join(ROOT, "docs", "img")

# thesis figure -> the file the block draws (relative to the work folder)
Z1, Z2L, Z2I = "out/z1_outf10/figures/", "out/z2_large/figures/", "out/z2_infini/figures/"
Z3, Z3B, Z4A, Z4B = "out/z3_data01/figures/", "out/z3_data02/figures/", "out/z4_v6_25/figures/", "out/z4_v50/figures/"
FIGURES = {
    "5_01": Z1 + "mesh_step0.png",
    "5_02": Z1 + "overlay_von_mises_steps7-4.png",
    "5_03i": Z1 + "overlay_stress_xy_steps7-4.png",
    "5_03ii": Z1 + "overlay_stress_yy_steps7-4.png",
    "5_03iii": Z1 + "overlay_stress_xx_steps7-4.png",
    "5_04": Z1 + "overlay_strain_xy_steps7-4.png",
    "5_04_step": Z1 + "overlay_strain_increment_xy_steps7-4.png",
    "5_05": Z1 + "overlay_displacement_y_steps7-4.png",
    "5_06": Z1 + "profile.png",
    "5_07": Z1 + "compare_pressure.png",
    "5_08i": Z2L + "mesh_step3.png",
    "5_08ii": Z2L + "mesh_steps6-3.png",
    "5_09": Z2L + "profile.png",
    "5_10": Z2I + "compare_von_mises_step6.png",
    "5_11i": Z2I + "compare_stress_xy_step6.png",
    "5_11ii": Z2I + "compare_stress_xx_step6.png",
    "5_11iii": Z2I + "compare_stress_yy_step6.png",
    "5_12i": Z2I + "compare_strain_xy_step6.png",
    "5_12ii": Z2I + "compare_strain_xx_step6.png",
    "5_12iii": Z2I + "compare_strain_yy_step6.png",
    "5_13": Z3 + "mesh_step0.png",
    "5_20": Z4A + "mesh_step0.png",
    "5_21i": "out/z4_figures/node101_z4_v6_25.png",
    "5_21ii": "out/z4_figures/node101_z4_v25.png",
    "5_21iii": "out/z4_figures/node101_z4_v50.png",
    "5_21iv": "out/z4_figures/node101_overlay.png",
    "5_21iv_soft": "out/z4_soft_figures/node101_overlay.png",
    "5_22": Z4A + "overlay_stress_xy_steps6-8-14-16.png",
    "5_23": Z4B + "overlay_stress_xy_steps6-8-14-16.png",
    "5_24": Z4B + "compare_von_mises_step4.png",
    "5_25": Z4B + "compare_von_mises_step12.png",
    "5_18": Z3B + "compare_von_mises_step47.png",
    "5_19": Z3B + "compare_stress_xy_step47.png",
}
for number, field in (("5_14", "von_mises"), ("5_15", "stress_xy"), ("5_16", "stress_xx"), ("5_17", "stress_yy")):
    for part, steps in (("i", "23-47"), ("ii", "23-71"), ("iii", "63-71")):
        FIGURES[number + part] = Z3 + "overlay_%s_steps%s.png" % (field, steps)


def block():
    """The shell commands between the markers of docs/figures.md."""
    text = open(FIGURES_MD).read()
    begin, end = "<!-- thesis-figures:begin -->", "<!-- thesis-figures:end -->"
    if begin not in text or end not in text:
        sys.exit("thesis_figures: %s has no %s ... %s block" % (FIGURES_MD, begin, end))
    body = text[text.index(begin) + len(begin):text.index(end)].strip()
    lines = body.splitlines()
    if lines[0].strip() != "```sh" or lines[-1].strip() != "```":
        sys.exit("thesis_figures: the block in %s is not one ```sh code block" % FIGURES_MD)
    return "\n".join(lines[1:-1]) + "\n"


def prepare(work, roller):
    """A scratch folder as the block expects it: a copy of problems/ (a scene's relative paths,
    such as z3_data02's ../out/z3_data01/state_final.cbor, must resolve inside the scratch folder,
    which through a link to problems/ they would not), links to the launcher and the binary."""
    os.makedirs(os.path.join(work, "build"), exist_ok=True)
    if not os.path.exists(os.path.join(work, "problems")):
        shutil.copytree(os.path.join(ROOT, "problems"), os.path.join(work, "problems"))
    if not os.path.exists(os.path.join(work, "rollerpy")):
        os.symlink(os.path.join(ROOT, "rollerpy"), os.path.join(work, "rollerpy"))
    link = os.path.join(work, "build", "roller")
    if not os.path.exists(link):
        os.symlink(os.path.abspath(roller), link)


def save_small(source, target):
    """The PNG with an adaptive 128-colour palette: line figures keep their look at a third of
    the size, so docs/img stays small."""
    from PIL import Image
    Image.open(source).convert("RGB").quantize(colors=128).save(target, optimize=True)


def main(argv=None):
    ap = parser("thesis-figures", __doc__)
    ap.add_argument("--roller", default=DEFAULT_ROLLER)
    ap.add_argument("--work", default=ROOT)
    ap.add_argument("--no-copy", action="store_true")
    args = ap.parse_args(argv)
    if not os.access(args.roller, os.X_OK):
        sys.exit("thesis_figures: --roller %s is not an executable (build it: bash scripts/build.sh)" % args.roller)
    work = os.path.abspath(args.work)
    if work != ROOT:
        prepare(work, args.roller)
    elif os.path.abspath(args.roller) != DEFAULT_ROLLER:
        sys.exit("thesis_figures: --roller other than build/roller needs --work (a scratch folder)")
    r = subprocess.run(["bash", "-euo", "pipefail", "-c", block()], cwd=work)
    if r.returncode != 0:
        sys.exit("thesis_figures: the block of %s stopped with exit %d (its output is above)"
                 % (FIGURES_MD, r.returncode))
    missing = [f for f in FIGURES.values() if not os.path.exists(os.path.join(work, f))]
    if missing:
        sys.exit("thesis_figures: not drawn: " + ", ".join(missing))
    if not args.no_copy:
        for number, source in sorted(FIGURES.items()):
            save_small(os.path.join(work, source), os.path.join(IMG, "thesis_%s.png" % number))
    print("thesis_figures: %d figures drawn%s" % (len(FIGURES), "" if args.no_copy else ", copied to " + IMG))
