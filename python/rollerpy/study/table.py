"""study.csv: one row per point — index, backend, the varied parameters, the collected values,
status, message, wall time, output folder — sorted by point, rewritten after every finished point
so that an interrupted study keeps what it has."""
import csv

from ..runner import atomic_file


def columns(study):
    return (["index", "backend"] + list(study.parameters) + list(study.collect)
            + ["status", "message", "wall_s", "out"])  # the runner's columns: study_file.RUNNER_COLUMNS


def row(study, record):
    r = {"index": record["index"], "backend": record["backend"] or "", "status": record["status"],
         "message": record["message"], "wall_s": record["wall_s"], "out": record["out"]}
    for k in study.parameters:
        r[k] = record["values"].get(k)
    for k in study.collect:
        r[k] = record["collected"].get(k)
    return r


def write(study, records, path):
    with atomic_file(path, newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns(study))
        w.writeheader()
        for record in sorted(records, key=lambda rec: rec["index"]):
            w.writerow({k: "" if v is None else v for k, v in row(study, record).items()})
