"""bench-passes runs the stationary method beside the marching backends: `stationary=N` in
--passes sets passes.method, and its passes are timed from solver.csv like theirs."""
import csv

from rollerpy.benchmarks.passes import main, run_options


def test_stationary_is_a_run_of_its_own_and_a_backend_name_stays_a_backend():
    assert run_options("stationary") == ["--set", 'passes.method="stationary"']
    assert run_options("stationary_hertz") == ["--set", 'passes.method="stationary"',
                                               "--set", 'passes.stationary_contact="hertz"']
    assert run_options("penalty") == ["--contact", "penalty"]


def test_stationary_passes_are_timed_per_pass(roller, tmp_path):
    main(["--roller", roller, "--out", str(tmp_path), "--element-size", "0.4", "--passes", "stationary=2"])
    with open(tmp_path / "passes.csv") as f:
        row, = list(csv.DictReader(f))
    assert row["backend"] == "stationary" and row["rc"] == "0"
    assert len(row["per_pass_s"].split()) == 2
    with open(tmp_path / "stationary_2passes" / "solver.csv") as f:
        assert len(list(csv.DictReader(f))) == 2  # one step a pass: the stationary method, not the march
    with open(tmp_path / "stationary_2passes" / "summary.json") as f:
        assert '"verdict"' in f.read()
