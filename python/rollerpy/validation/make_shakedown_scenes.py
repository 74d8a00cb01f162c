"""Writes the shakedown validation scenes problems/shakedown_pXX.toml (docs/validation.md,
"Shakedown: repeated rolling of a line contact").

usage: ./rollerpy make-shakedown-scenes [--loads 3.0,3.7,4.5,5.5] [--passes 5]
                                      [--element-size 0.2] [--out problems]
                                      [--kinematic E_T] [--track 8] [--step 0.5] [--periodic]
                                      [--continuous] [--traction Q/P --friction MU]

One template, the load as p0/k in the name: a rigid cylinder R = 100 mm rolled frictionlessly
over an elastic-perfectly plastic strip (E = 2.1e5 MPa, nu = 0.3, E_T = 0) under a constant
force P = 7250 N/mm, so that the Hertz half-width is a = 2 mm and p0 = a E*/(2R) = 2308 MPa; the
yield stress sets the load ratio: k = sigma_y/sqrt(3) = p0/(p0/k). The strip, 200 x 100 mm with
its base bonded, acts as a half-space under the track: uniform 0.2 mm elements (20 across 2a)
over x = 88...112 and the top 6 mm, graded outside. One pass: press to P at x = 92 (steps 1-3),
roll 16 mm = 8a to x = 108 under P (steps 4-19, 0.5a per step), lift 0.3 mm (steps 20-21); the
window of passes.csv is then x = 96...104. --element-size changes the uniform size (0.1: 40
elements across 2a, 4.8e4 dofs, the strip of `rollerpy bench-passes`) and --out the folder.
--kinematic E_T writes problems/shakedown_kinematic_pXX.toml instead: the same strip with linear
kinematic (Prager) hardening of tangent modulus E_T, whose cycles above Johnson's 4.0 close
(plastic shakedown) where the perfectly plastic strip ratchets (docs/validation.md).
--track T and --step S (in units of a) roll T a in steps of S a instead of 8a in 0.5a: the
uniform elements then reach 2a past the travel's end, and the window is the middle half of the
longer track (the long transient passes of docs/validation.md, "Stationary passes against
transient passes"). --periodic makes the strip one period of an endless track, the track itself
(uniform elements over 2a T, `[mesh] periodic`): the roller presses in its middle, rolls the whole
period over the seam and lifts where it pressed, so no stretch is left unrolled and the rolled
layer has no ends to relieve it. --continuous (with --periodic) rolls the ring without lifting: one
press, then --passes periods rolled on, fields written every period, when the roller stands 3 steps
before where it pressed; the half of the ring opposite it has then been rolled over once more (a
ring that is pressed and lifted every pass compresses the rest of it with its press zone).
--traction Q/P --friction MU rolls under the horizontal force Q (roller.path fx, ramped up over
the first 2a and taken off with the roller standing after the track, one step more a pass) with
Coulomb friction MU instead of freely: Carter's steady rolling, the creep an outcome
(docs/validation.md, "Rolling under a tangential force").
"""
import math
import os

from ..command import parser
from ..paths import PROBLEMS

E, NU, R, A = 2.1e5, 0.3, 100.0, 2.0
E_STAR = E / (1.0 - NU ** 2)
LOAD = math.pi * A ** 2 * E_STAR / (4.0 * R)
P0 = A * E_STAR / (2.0 * R)
PRESS_STEPS = 3  # the press to P, the first steps of a pass (stationary-check's rolled-on ring reads it)


def graded(x0, x1, h_fine, n, fine_at_end):
    """n intervals from x0 to x1, geometric, the interval at the fine end h_fine."""
    length = x1 - x0
    # ratio q with h (q^n - 1)/(q - 1) = length, by bisection
    lo, hi = 1.0 + 1e-9, 3.0
    for _ in range(200):
        q = 0.5 * (lo + hi)
        if h_fine * (q ** n - 1.0) / (q - 1.0) > length:
            hi = q
        else:
            lo = q
    sizes = [h_fine * q ** i for i in range(n)]
    sizes = [s * length / sum(sizes) for s in sizes]
    if fine_at_end:
        sizes = sizes[::-1]
    out, x = [], x0
    for s in sizes[:-1]:
        x += s
        out.append(x)
    return out


def lines(h, track):
    """Uniform h from 2a before the press to 2a past the travel's end, graded 88 mm either side."""
    fine = A * track + 4.0 * A
    bands = (("the 6 mm band under the surface", 6.0), ("the %g mm of the track and 2a either side" % fine, fine))
    for what, extent in bands:
        n = int(round(extent / h))
        if n < 1 or abs(n * h - extent) > 1e-9 * extent:
            raise SystemExit("make-shakedown-scenes: elements of %g mm do not fill %s: give an element size that "
                             "divides it (e.g. 0.5, 0.4, 0.25, 0.2)" % (h, what))
    end = 88.0 + fine
    xs = [0.0] + graded(0.0, 88.0, h, 24, fine_at_end=True)
    xs += [88.0 + h * i for i in range(int(round(fine / h)) + 1)]
    xs += graded(end, end + 88.0, h, 24, fine_at_end=False) + [end + 88.0]
    ys = [0.0] + graded(0.0, 94.0, h, 22, fine_at_end=True)
    ys += [94.0 + h * i for i in range(int(round(6.0 / h)) + 1)]
    return xs, ys


def fmt_lines(values):
    text = ", ".join("%.6g" % v for v in values)
    out, line = [], "  "
    for item in text.split(", "):
        if len(line) + len(item) > 96:
            out.append(line.rstrip())
            line = "  "
        line += item + ", "
    out.append(line.rstrip().rstrip(","))
    return "[\n" + "\n".join(out) + "\n]"


def hardening_lines(kinematic):
    """The [material] lines after yield_stress: perfectly plastic, or Prager with E_T."""
    if kinematic is None:
        return "tangent_modulus = 0.0"
    return 'hardening = "kinematic"     # Prager: the yield surface moves, C = H\'\ntangent_modulus = %g' % kinematic


def periodic_lines(h, track):
    """A periodic strip of one period, the track: uniform h along x, y as lines()'s."""
    n = int(round(A * track / h))
    if n < 2 or abs(n * h - A * track) > 1e-9 * A * track:
        raise SystemExit("make-shakedown-scenes: --track %g a is not a whole number of elements of %g mm" % (track, h))
    return [h * i for i in range(n + 1)], lines(h, track)[1]


def roll_segments(start, rolls, step, load, traction):
    """The path's rolling segments over steps start ... start + rolls - 1, `step` a each, under P =
    `load`: one segment when it rolls freely; under the horizontal force Q = traction P along the
    travel (roller.path fx, the strip's force on the roller: -Q), the force ramped up over the first
    2a, then held, then a step that takes it off with the roller standing (so that nothing is left
    for the lift to carry). Returns the text and the number of steps."""
    travel = round(A * rolls * step, 6)
    if traction is None:
        return """[[roller.path]]         # roll {track:g}a under P
steps = [{start}, {end}]
dx = {travel!r}
fy = {load:.4f}""".format(track=rolls * step, start=start, end=start + rolls - 1, travel=travel, load=load), rolls
    ramp = min(rolls - 1, max(1, int(round(2.0 / step))))
    if ramp < 1:
        raise SystemExit("make-shakedown-scenes: --traction needs a track of at least two steps")
    fx = -traction * load
    return """[[roller.path]]         # roll {ramp_a:g}a under P while Q = {traction:g} P builds up (fx = -Q)
steps = [{start}, {ramp_end}]
dx = {ramp_dx!r}
fy = {load:.4f}
fx = {fx:.4f}

[[roller.path]]         # roll on under P and Q: {track:g}a in all
steps = [{rest_start}, {end}]
dx = {rest_dx!r}
fy = {load:.4f}
fx = {fx:.4f}

[[roller.path]]         # Q taken off, the roller standing
steps = [{off}, {off}]
fy = {load:.4f}
fx = 0.0""".format(ramp_a=ramp * step, traction=traction, start=start, ramp_end=start + ramp - 1,
                   ramp_dx=round(A * ramp * step, 6), load=load, fx=fx, track=rolls * step, rest_start=start + ramp,
                   end=start + rolls - 1, rest_dx=round(travel - A * ramp * step, 6), off=start + rolls), rolls + 1


def repeated_passes(passes, rolls, step, load, traction=None):
    """[steps], [passes] and [output], and the path after the press, of repeated passes: press,
    roll the track (under the horizontal force traction P, roll_segments), lift clear, fields after
    every pass."""
    roll_block, roll_steps = roll_segments(PRESS_STEPS + 1, rolls, step, load, traction)
    count = roll_steps + PRESS_STEPS + 2
    steps = """[steps]
count = {count}              # one pass

[passes]
count = {passes}

[output]
every = {count}              # fields at the end of every pass""".format(count=count, passes=passes)
    path = """{roll_block}

[[roller.path]]         # lift clear
steps = [{lift_start}, {count}]
dy = 0.3""".format(roll_block=roll_block, lift_start=roll_steps + PRESS_STEPS + 1, count=count)
    return steps, path


def rolled_on(passes, rolls, track, step, load):
    """[steps] and [output], and the path after the press, of a ring rolled on: `passes` periods of
    `rolls` steps, the press the first PRESS_STEPS of them, then rolling on under P to the last
    step; fields every period (the roller then PRESS_STEPS steps before where it pressed)."""
    steps = """[steps]
count = {count}              # one press, {passes} periods rolled on

[output]
every = {rolls}              # fields every period""".format(count=passes * rolls, passes=passes, rolls=rolls)
    path = """[[roller.path]]         # roll on under P, {passes} periods less the press's {press} steps
steps = [{start}, {end}]
dx = {travel!r}
fy = {load:.4f}""".format(passes=passes, press=PRESS_STEPS, start=PRESS_STEPS + 1, end=passes * rolls,
                          travel=round((passes * rolls - PRESS_STEPS) * step * A, 6), load=load)
    return steps, path


def scene(ratio, passes, h, kinematic=None, track=8.0, step=0.5, periodic=False, continuous=False, traction=None,
          friction=0.0):
    """The scene's name and text; track and step in units of a (the shipped scenes: 8a in 0.5a).
    traction: the roller rolls under the horizontal force Q = traction P along the travel (Carter's
    problem, which needs friction >= traction) instead of freely.
    periodic: the strip is one period of an endless track, the track itself (docs/model.md,
    Periodic strip): the roller presses in its middle, rolls the whole period over the seam and
    lifts where it pressed, and no stretch of the strip is left unrolled. continuous: it presses
    once and rolls `passes` periods on (rolled_on)."""
    sigma_y = math.sqrt(3.0) * P0 / ratio
    xs, ys = periodic_lines(h, track) if periodic else lines(h, track)
    press_x = 0.5 * A * track if periodic else 92.0
    rolls = int(round(track / step))
    if rolls < 1 or abs(rolls * step - track) > 1e-9 * track:
        raise SystemExit("make-shakedown-scenes: --track %g is not a whole number of --step %g" % (track, step))
    if continuous and not periodic:
        raise SystemExit("make-shakedown-scenes: --continuous rolls a ring: give --periodic too")
    prefix = "shakedown_p" if kinematic is None else "shakedown_kinematic_p"
    name = prefix + "%02d" % round(10 * ratio)
    law = "elastic-perfectly plastic strip" if kinematic is None else "Prager-hardening strip"
    if traction is not None and not 0.0 < traction <= friction:
        raise SystemExit("make-shakedown-scenes: --traction %g needs 0 < Q/P <= --friction (%g)" % (traction, friction))
    if traction is not None and continuous:
        raise SystemExit("make-shakedown-scenes: --traction with --continuous is not written")
    steps_block, path_block = (rolled_on(passes, rolls, track, step, LOAD) if continuous else
                               repeated_passes(passes, rolls, step, LOAD, traction))
    rolling = ("Frictionless rolling" if traction is None else
               "Rolling under Q = %g P (friction %g)" % (traction, friction))
    return name, """# Shakedown validation at p0/k = {ratio}: written by `./rollerpy make-shakedown-scenes` (edit
# python/rollerpy/validation/make_shakedown_scenes.py, not this file); docs/validation.md,
# "Shakedown: repeated rolling of a line contact".
# {rolling} of a rigid cylinder (R = 100 mm) under P = {load:.1f} N/mm over an
# {law}: Hertz a = {a} mm, p0 = {p0:.1f} MPa, k = sigma_y/sqrt(3) =
# {k:.1f} MPa. Johnson: first yield at p0/k = 3.1, elastic shakedown limit 4.0.
title = "Shakedown: {title_rolling} at p0/k = {ratio}, {passes} passes{title_law}"
kinematics = "small"

[mesh]
element = "Q4"
length = {length!r}
height = 100.0{periodic}
x_lines = {xl}
y_lines = {yl}
q4_formulation = "bbar"

[material]
E = {E}
nu = {NU}
yield_stress = {sy:.4f}
{hardening}

{steps_block}

[[displacement]]        # the half-space's far field: base bonded
nodes = "bottom"
x = 0.0
y = 0.0

[roller]
radius = {R}
centre = [{press_x!r}, 200.0]  # touching the top at x = {press_x:g}

[[roller.path]]         # press to P
steps = [1, {press}]
fy = {load:.4f}

{path_block}

[contact]
backend = "ipopt"
friction = {friction!r}
""".format(rolling=rolling, title_rolling=rolling[0].lower() + rolling[1:], friction=float(friction),
           ratio=ratio, load=LOAD, a=A, p0=P0, k=P0 / ratio, passes=passes, xl=fmt_lines(xs), yl=fmt_lines(ys),
           E=E, NU=NU, sy=sigma_y, R=R, law=law, hardening=hardening_lines(kinematic),
           title_law=("" if kinematic is None else ", kinematic hardening") + (", rolled on" if continuous else ""),
           length=round(xs[-1], 6), press_x=press_x,
           periodic="\nperiodic = true        # one period of an endless track" if periodic else "",
           steps_block=steps_block, path_block=path_block, press=PRESS_STEPS)


def write_scenes(loads, passes, element_size, out, kinematic=None, track=8.0, step=0.5, periodic=False,
                 continuous=False, traction=None, friction=0.0):
    """problems/shakedown_pXX.toml for each load p0/k into `out`; returns the paths written."""
    os.makedirs(out, exist_ok=True)
    written = []
    for ratio in loads:
        name, text = scene(ratio, passes, element_size, kinematic, track, step, periodic, continuous, traction,
                           friction)
        path = os.path.join(out, name + ".toml")
        with open(path, "w") as f:
            f.write(text)
        written.append(path)
    return written


def main(argv=None):
    ap = parser("make-shakedown-scenes", __doc__)
    ap.add_argument("--loads", default="3.0,3.7,4.5,5.5")
    ap.add_argument("--passes", type=int, default=5)
    ap.add_argument("--element-size", type=float, default=0.2)
    ap.add_argument("--out", default=PROBLEMS)
    ap.add_argument("--kinematic", type=float, default=None, metavar="E_T",
                    help="linear kinematic hardening with this tangent modulus [MPa]")
    ap.add_argument("--track", type=float, default=8.0, help="the roller's travel under load, in units of a")
    ap.add_argument("--step", type=float, default=0.5, help="the roller's travel per step, in units of a")
    ap.add_argument("--periodic", action="store_true",
                    help="the strip one period (the track) of an endless track: no track ends")
    ap.add_argument("--continuous", action="store_true",
                    help="with --periodic: press once and roll --passes periods on, fields every period")
    ap.add_argument("--traction", type=float, default=None, metavar="Q/P",
                    help="roll under the horizontal force Q = Q/P x P along the travel (needs --friction)")
    ap.add_argument("--friction", type=float, default=0.0)
    args = ap.parse_args(argv)
    loads = [float(r) for r in args.loads.split(",")]
    for path in write_scenes(loads, args.passes, args.element_size, args.out, args.kinematic,
                             args.track, args.step, args.periodic, args.continuous, args.traction,
                             args.friction):
        print("wrote", path)
