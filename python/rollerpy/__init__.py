"""rollerpy: the Python side of roller (docs/python.md). runner starts roller, outputs and vtu read
what it writes, scan looks for nan/inf in it, plots draws figures, study runs parameter sweeps,
validation and benchmarks hold the suites; `python3 -m rollerpy COMMAND` runs each of them."""
