"""rollerpy COMMAND [OPTIONS]: every Python tool of roller as one command (docs/python.md).
`./rollerpy COMMAND --help` (the launcher at the checkout's root) or, with PYTHONPATH=python,
`/usr/bin/python3 -m rollerpy COMMAND --help` shows a command's options."""
import argparse
import importlib
import sys

# command -> (module with main(argv), what it does); a module is imported only when its command runs.
COMMANDS = {
    "study": ("rollerpy.study.cli", "run every point of a study file (docs/studies.md)"),
    "plot-scene": ("rollerpy.plots.scene", "thesis-style figures of an output folder (docs/figures.md)"),
    "plot-forces": ("rollerpy.plots.forces", "the roller's force and position against the step"),
    "plot-passes": ("rollerpy.plots.passes", "a multi-pass run's figures: passes, residual_depth, fatigue .png"),
    "plot-node-history": ("rollerpy.plots.node_history", "one node's displacement increments over the steps"),
    "plot-monotonicity": ("rollerpy.plots.monotonicity", "maps of `roller monotonicity` (docs/monotonicity.md)"),
    "plot-shakedown-map": ("rollerpy.plots.shakedown_map", "the shakedown map of a study.csv"),
    "material-loops": ("rollerpy.plots.material_loops", "a scene's material in uniaxial loops and ratchetting"),
    "rcf-map": ("rollerpy.plots.rcf_map", "a steel's rolling-contact-fatigue map: Johnson's regions, Ekberg's limits"),
    "plot-melan-map": ("rollerpy.plots.melan_map", "roller shakedown-limit --map's map against Johnson's limits"),
    "shakedown-map": ("rollerpy.validation.shakedown_map", "run the shakedown-map study and draw the map"),
    "shakedown": ("rollerpy.validation.shakedown", "repeated rolling against Johnson's shakedown results"),
    "melan-check": ("rollerpy.validation.melan_check", "transient passes 5 % below and above Melan's limit"),
    "make-shakedown-scenes": ("rollerpy.validation.make_shakedown_scenes", "write problems/shakedown_pXX.toml"),
    "stationary-check": ("rollerpy.validation.stationary_check", "stationary passes against long transient passes"),
    "carter": ("rollerpy.validation.carter", "steady rolling with creep against Carter's theory"),
    "cattaneo-mindlin": ("rollerpy.validation.cattaneo_mindlin", "Cattaneo's stick zone under prescribed forces"),
    "rolling-suite": ("rollerpy.validation.rolling_suite", "rolling-friction robustness suite"),
    "stability": ("rollerpy.validation.stability", "stiff and extreme cases on both backends"),
    "check-scene-outputs": ("rollerpy.validation.check_scene_outputs",
                            "every shipped scene, both backends: converged, no nan or inf"),
    "fuzz-scenes": ("rollerpy.validation.fuzz_scenes", "mutation fuzzer of scenes and options"),
    "fuzz-shakedown-limit": ("rollerpy.validation.fuzz_shakedown_limit",
                             "fuzzer of roller shakedown-limit: options, output paths"),
    "fuzz-python": ("rollerpy.validation.fuzz_python", "fuzzer of rollerpy.run: dict scenes, keywords, threads"),
    "fuzz-study": ("rollerpy.validation.fuzz_study", "fuzzer of study files: values, collect outside a point"),
    "z2-table": ("rollerpy.validation.z2_table", "thesis Table 5.1 from the Z2 runs"),
    "thesis-figures": ("rollerpy.validation.thesis_figures", "draw every figure of the thesis's chapter 5"),
    "thesis-statements": ("rollerpy.validation.thesis_statements", "measure the chapter-5 statements"),
    "bench-error-vs-time": ("rollerpy.benchmarks.error_vs_time", "error against run time, penalty vs ipopt"),
    "bench-passes": ("rollerpy.benchmarks.passes", "time of repeated passes under load"),
    "bench-scaling": ("rollerpy.benchmarks.scaling", "scaling of one increment with the number of dofs"),
}


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    listing = "\n".join("  %-22s %s" % (name, what) for name, (_, what) in COMMANDS.items())
    ap = argparse.ArgumentParser(prog="rollerpy", description=__doc__, epilog="commands:\n" + listing,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=COMMANDS, metavar="COMMAND")
    ap.add_argument("options", nargs=argparse.REMAINDER, help="the command's options (COMMAND --help)")
    if not argv:
        ap.print_help()
        return 2
    if argv[0] not in COMMANDS:
        ap.parse_args(argv)  # prints the help, or names the unknown command, and exits
    module = importlib.import_module(COMMANDS[argv[0]][0])
    return module.main(argv[1:]) or 0


if __name__ == "__main__":
    sys.exit(main())
