"""rollerpy: the Python side of roller (docs/python.md). run and load_scene run roller in this
process (inprocess, the native module _roller); runner starts roller as a program, outputs and
vtu read what it writes, scan looks for nan/inf in it, plots draws figures, study runs parameter
sweeps, validation and benchmarks hold the suites; `python3 -m rollerpy COMMAND` runs each of
them."""

# The in-process names, imported when first used: the rest of the package works without the
# native module (e.g. beside the sanitizer build, which does not build it).
_INPROCESS = {"run", "load_scene", "RunResult", "RunInterrupted", "InputError", "ResourceError", "Scene",
              "version"}


def __getattr__(name):
    if name in _INPROCESS:
        from rollerpy import inprocess
        return getattr(inprocess, name)
    raise AttributeError(f"module 'rollerpy' has no attribute '{name}'")


def __dir__():
    # The in-process names too, for dir() and completion (they are imported when first used).
    return sorted(set(globals()) | _INPROCESS)
