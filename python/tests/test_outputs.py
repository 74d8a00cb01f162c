"""The reader (rollerpy.outputs, rollerpy.vtu) on files roller writes and on a VTU written here:
a VTU round-trips raw and zlib-compressed, the arrays of a run's VTU match its piece and its
tables (points, cells, the roller's last step), the CSV readers give the rows and numbers of the
files, fields.pvd names every step; and the nan/inf scanner finds planted values."""
import os
import subprocess

import numpy as np
import pytest
from conftest import run_scene

from rollerpy import outputs, scan, vtu
from rollerpy.paths import ROOT


@pytest.fixture(scope="module")
def hertz_out(roller, tmp_path_factory):
    return run_scene(roller, "hertz", str(tmp_path_factory.mktemp("reader")))


@pytest.mark.parametrize("compressed", [True, False])
def test_a_written_vtu_reads_back(tmp_path, compressed):
    u = np.arange(8.0).reshape(4, 2) - 3.5
    path = str(tmp_path / "two.vtu")
    vtu.write_test_vtu(path, u, compressed)
    step = vtu.read_vtu(path)
    np.testing.assert_array_equal(step.point_data["displacement"], u)
    np.testing.assert_array_equal(step.points, [[0, 0], [1, 0], [1, 1], [0, 1]])
    assert [list(e) for e in step.elements] == [[0, 1, 2], [0, 2, 3]]
    assert step.cell_data["stress"].shape == (2, 4)


def test_a_cut_vtu_array_is_malformed(tmp_path):
    path = str(tmp_path / "short.vtu")
    vtu.write_test_vtu(path, np.zeros((3, 2)), True)  # three tuples in a piece of four points
    with pytest.raises(vtu.VtuError, match="PointData/displacement: 6 values, expected 8"):
        vtu.read_vtu(path)


def test_the_vtu_of_a_run_matches_its_piece_and_tables(hertz_out):
    steps = vtu.available_steps(hertz_out)
    assert steps == list(range(len(steps))) and len(steps) > 1
    assert sorted(vtu.step_times(hertz_out)) == steps
    last = vtu.read_vtu(vtu.vtu_path(hertz_out, steps[-1]))
    with open(vtu.vtu_path(hertz_out, steps[-1])) as f:
        head = f.read(1000)
    assert 'NumberOfPoints="%d" NumberOfCells="%d"' % (len(last.points), len(last.elements)) in head
    assert all(len(e) == 4 for e in last.elements)  # Hertz: Q4
    assert last.point_data["displacement"].shape == (len(last.points), 3)
    assert last.cell_data["von_mises"].shape == (len(last.elements),)
    assert np.isfinite(last.cell_data["stress"]).all() and np.abs(last.cell_data["stress"]).max() > 0
    points0, elements0 = vtu.reference_mesh(hertz_out)
    np.testing.assert_allclose(points0 + last.point_data["displacement"][:, :2], last.points, atol=1e-9)
    assert len(elements0) == len(last.elements)
    top = vtu.top_nodes(points0)
    assert len(top) > 2 and np.allclose(points0[top, 1], points0[:, 1].max())
    assert len(vtu.triangles(last.elements)) == 2 * len(last.elements)


def test_a_csv_with_text_columns_as_a_numpy_array(tmp_path):
    path = str(tmp_path / "slices.csv")
    with open(path, "w") as f:
        f.write("panel,resolution,a,lambda_min\na,fine,1.5,-2\nb,coarse,3,4e3\n")
    data = outputs.read_array(path, n_text=2)
    assert list(data["panel"]) == ["a", "b"] and list(data["resolution"]) == ["fine", "coarse"]
    np.testing.assert_array_equal(data["lambda_min"], [-2.0, 4000.0])


def test_the_tables_of_a_run(hertz_out):
    roller = outputs.read_rows(os.path.join(hertz_out, "roller.csv"))
    solver = outputs.read_numbers(os.path.join(hertz_out, "solver.csv"))
    steps = vtu.available_steps(hertz_out)
    assert [int(r["step"]) for r in roller] == steps
    assert [int(r["step"]) for r in solver] == steps[1:]
    assert all(r["status"] == "converged" and r["iterations"] >= 1 for r in solver)
    assert outputs.read_rows(os.path.join(hertz_out, "nothing.csv"), missing_ok=True) == []
    summary = outputs.read_summary(hertz_out)
    assert summary["converged"] is True
    collected = outputs.collect(hertz_out, ["converged", "solver.csv:iterations", "no.such.key"])
    assert collected == {"converged": True, "solver.csv:iterations": "%d" % solver[-1]["iterations"],
                         "no.such.key": None}
    contact = outputs.read_contact(hertz_out)
    profile = outputs.contact_profile(contact, steps[-1])
    assert list(profile.x) == sorted(profile.x) and profile.p_n.max() > 0
    touching = outputs.touching_x(contact, steps[-1])
    assert touching and min(touching) >= profile.x[0] and max(touching) <= profile.x[-1]
    pose = outputs.roller_at(hertz_out, steps[-1])
    assert pose.xc == pytest.approx(float(roller[-1]["xc"]))
    assert pose.radius == outputs.read_scene(hertz_out)["roller"]["radius"]
    assert outputs.num("x") != outputs.num("x") and outputs.num("2.5") == 2.5


def test_a_run_scans_clean_and_the_scanner_finds_planted_values(hertz_out):
    assert scan.self_check() == []
    folder = scan.scan_outputs(hertz_out)
    assert folder.flagged == [] and folder.vtu_files == len(vtu.available_steps(hertz_out))
    assert folder.arrays >= 19 * folder.vtu_files


def test_files_named_for_writing_are_new_or_regular_and_written_atomically(tmp_path, hertz_out):
    """As roller's --csv/--json: a link, a FIFO or a folder is refused and left as it was; a regular
    file is replaced whole; the temporary file is never written through a link."""
    from rollerpy.runner import atomic_file, output_file_problem
    victim = tmp_path / "victim.png"
    victim.write_text("keep me\n")
    (tmp_path / "link.png").symlink_to(victim)
    os.mkfifo(tmp_path / "fifo.png")
    assert "expected a file name" in output_file_problem("", "--output")
    for name in ("link.png", "fifo.png", "."):
        assert "something other than a regular file" in output_file_problem(str(tmp_path / name), "--output")
    assert "does not exist" in output_file_problem(str(tmp_path / "no" / "x.png"), "--output")
    assert output_file_problem(str(victim), "--output") == ""
    (tmp_path / "new.png.tmp").symlink_to(victim)
    with pytest.raises(OSError):
        with atomic_file(str(tmp_path / "new.png")) as f:
            f.write("x")
    assert victim.read_text() == "keep me\n" and not (tmp_path / "new.png").exists()
    with atomic_file(str(victim)) as f:
        f.write("new\n")
    assert victim.read_text() == "new\n" and (tmp_path / "link.png").is_symlink()
    for name in ("fifo.png", "link.png"):
        r = subprocess.run([os.path.join(ROOT, "rollerpy"), "plot-forces", hertz_out, "--output", str(tmp_path / name)],
                           capture_output=True, text=True)
        assert r.returncode == 2 and "regular file" in r.stderr, r.stderr
    assert (tmp_path / "fifo.png").is_fifo() and victim.read_text() == "new\n"
