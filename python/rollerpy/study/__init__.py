"""Studies: one runner for every parameter sweep (docs/studies.md). study_file reads and checks a
study file, point runs one roller process for one point, engines run the points serially or on
a Dask cluster (local by default), table writes study.csv, cli is the `study` command."""
