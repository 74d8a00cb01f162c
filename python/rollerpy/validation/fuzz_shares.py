"""The shares of fuzz-scenes' cases with rules of their own (docs/stability.md, "Hostile input"):
multi-pass scenes solved with the stationary method, [[layer]] blocks added to a scene, and one
--set key given twice with a non-finite value among them. Each returns the case's scene text or
options, what it did, and why the case must end in exit 2 ("" when any documented code will do)."""

# Multi-pass scenes with the stationary method: 1 or 2 passes of one step each (1-4 s with the
# release build). The smallest mesh weighs most; under ASan (--sanitized) only it, one pass.
PASS_SEEDS = ["shakedown_case_hardened", "shakedown_thin_strip", "shakedown_case_hardened", "shakedown_p45"]
SMALL_PASS_SEEDS = ["shakedown_case_hardened"]
# Values of the [passes] keys that must be refused (never a valid one that would run for long,
# such as passes.count = 9999 or 16 phases).
BAD_PASS_VALUES = {
    "passes.count": ["0", "-1", "nan", "inf", "1e308", "10001", "4294967297", "2.5", '"2"', "[]"],
    "passes.stationary_phases": ["0", "17", "-1", "nan", "inf", "1e308", "2.5", '"x"'],
    "passes.stationary_path_parts": ["0", "65", "-1", "nan", "1e20", '"16"'],
    "passes.stationary_contact": ['"Hertz"', '"penalty"', '""', "1", "nan", "[]"],
    "passes.method": ['"steady"', '""', "true", "nan"],
    "passes.until_verdict": ['"yes"', "1", "nan"],
}
# Layer keys with values that run, and the [[layer]] keys that are picked among.
LAYER_VALUES = {
    "thickness": ["0.05", "0.5", "1.0", "1.5"],
    "E": ["3.0e5", "1.5e5"],
    "nu": ["0.25", "0.35"],
    "yield_stress": ["2500.0", "400.0", "1200.0"],
    "tangent_modulus": ["0.0", "5000.0"],
    "kappa": ["0.05"],
    "density": ["7.8e-9"],
    "hardening": ['"isotropic"', '"kinematic"'],
}
# --set keys given twice, each with a value that runs when given once.
TWICE = [("material.E", "2.1e5"), ("material.nu", "0.3"), ("material.yield_stress", "800.0"),
         ("steps.dt", "1.0"), ("contact.friction", "0.1"), ("roller.radius", "50.0")]
NONFINITE = ["nan", "inf", "-inf", "+nan", "-nan"]


def set_words(values):
    words = []
    for key, value in values:
        words += ["--set", "%s=%s" % (key, value)]
    return words


def pass_case(rng, sanitized):
    """Options that make a multi-pass scene a short stationary run (--refine 1 now and then); one
    case in seven with a value of a [passes] key that must be refused, one in ten with --steps,
    which a multi-pass scene must refuse."""
    values = [("passes.method", '"stationary"'), ("passes.count", rng.choice(["1"] if sanitized else ["1", "1", "2"]))]
    if rng.random() < 0.6:
        values.append(("passes.stationary_contact", rng.choice(['"hertz"', '"roller"'])))
    if rng.random() < 0.3:
        values.append(("passes.stationary_phases", rng.choice(["1", "2"])))
    if rng.random() < 0.2:
        values.append(("passes.stationary_path_parts", rng.choice(["1", "4", "16"])))
    if rng.random() < 0.2:
        values.append(("passes.until_verdict", rng.choice(["true", "false"])))
    if rng.random() < 0.15:
        values.append(("passes.direction", '"alternate"'))
    due = ""
    if rng.random() < 1.0 / 7.0:
        key = rng.choice(sorted(BAD_PASS_VALUES))
        bad = rng.choice(BAD_PASS_VALUES[key])
        values = [kv for kv in values if kv[0] != key] + [(key, bad)]
        due = "%s = %s" % (key, bad)
    options = set_words(values)
    if rng.random() < 0.1:
        options += ["--steps", rng.choice(["1", "2", "21"])]
        due = due or "--steps with a multi-pass scene"
    if rng.random() < 0.2:
        options += ["--refine", "1"]
    return options, " ".join(options), due


def layer_case(text, rng, hostile):
    """The scene with [[layer]] blocks appended (1-3, now and then 200 thin ones), mostly with
    values that run, one value in six from `hostile`; --set mesh.follow_layers = true now and then."""
    n = rng.choice([1, 1, 2, 3, 200])
    blocks = []
    for _ in range(n):
        lines = ["[[layer]]"]
        keys = ["thickness"] + rng.sample(sorted(set(LAYER_VALUES) - {"thickness"}), rng.randrange(0, 3))
        if rng.random() < 0.05:
            keys.remove("thickness")
        for key in keys:
            choices = ["0.001"] if n == 200 and key == "thickness" else LAYER_VALUES[key]
            lines.append("%s = %s" % (key, rng.choice(hostile if rng.random() < 1.0 / 6.0 else choices)))
        blocks.append("\n".join(lines))
    options = ["--set", "mesh.follow_layers=true"] if rng.random() < 0.3 else []
    what = "%d [[layer]] block%s (first: %s)%s" % (n, "s" if n > 1 else "", blocks[0].replace("\n", "; "),
                                                   ", follow_layers" if options else "")
    return text.rstrip("\n") + "\n\n" + "\n\n".join(blocks) + "\n", options, what


def twice_case(rng):
    """One key given twice with --set, a non-finite value first or last: exit 2 is due (a value
    that later one hides is still a value given)."""
    key, good = rng.choice(TWICE)
    bad = rng.choice(NONFINITE)
    values = [(key, bad), (key, good)] if rng.random() < 0.7 else [(key, good), (key, bad)]
    options = set_words(values)
    return options, " ".join(options), "%s given twice, once as %s" % (key, bad)
