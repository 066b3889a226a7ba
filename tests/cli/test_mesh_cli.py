"""``voxfab mesh`` through the real entry point."""

import json
import subprocess
import sys

import numpy as np
import pytest

from voxfab.cli import main
from voxfab.fabricate.mesh import read_mesh
from voxfab.shape import examples


@pytest.fixture
def shape_file(tmp_path):
    path = tmp_path / "tunnel.npy"
    np.save(path, examples.tunnel_cube(5))
    return path


def test_writes_3mf_and_reports(tmp_path, shape_file, capsys):
    out = tmp_path / "t.3mf"
    assert main(["mesh", str(shape_file), "-o", str(out), "--pitch", "2", "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["volume_mm3"] == pytest.approx(648.0) and info["parts"] == 1
    assert len(read_mesh(out).triangles) == info["triangles"]


def test_prints_mass_time_and_the_spin_check(tmp_path, shape_file, capsys):
    out = tmp_path / "t.3mf"
    assert main(["mesh", str(shape_file), "-o", str(out), "--pitch", "2", "--spin", "--infill", "40"]) == 0
    printed = capsys.readouterr()
    assert "g of PLA at 40 % infill, about " in printed.out and "as a top it wobbles" in printed.out
    assert "spin: the lowest point is not a single tip" in printed.err
    assert main(["mesh", str(shape_file), "-o", str(tmp_path / "u.3mf"), "--infill", "120"]) == 3
    assert not (tmp_path / "u.3mf").exists()


def test_size_and_thin_wall_warning(tmp_path, shape_file):
    out = tmp_path / "t.stl"
    run = subprocess.run(
        [sys.executable, "-m", "voxfab", "mesh", str(shape_file), "-o", str(out), "--size", "2.5"],
        capture_output=True, text=True,
    )
    assert run.returncode == 0, run.stderr
    assert "voxfab: warning:" in run.stderr and "0.8 mm" in run.stderr
    assert "2.5 x 2.5 x 2.5 mm" in run.stdout
    assert out.stat().st_size == 84 + 50 * len(read_mesh(out).triangles)


def test_contacts_error_lists_them(tmp_path, capsys):
    g = np.zeros((2, 2, 1), bool)
    g[0, 0, 0] = g[1, 1, 0] = True
    src = tmp_path / "pair.npy"
    np.save(src, g)
    out = tmp_path / "pair.obj"
    assert main(["mesh", str(src), "-o", str(out), "--contacts", "error"]) == 10
    err = capsys.readouterr().err
    assert err.startswith("voxfab: error:") and "(0,0,0)-(1,1,0)" in err
    assert not out.exists()
    assert main(["mesh", str(src), "-o", str(out), "--contacts", "split"]) == 0
    assert read_mesh(out).part_count == 2


def test_bad_options_are_one_line_errors(tmp_path, shape_file, capsys):
    assert main(["mesh", str(shape_file), "-o", str(tmp_path / "x.step")]) == 4
    assert main(["mesh", str(shape_file), "-o", str(tmp_path / "x.glb"), "--magnet", "big"]) == 3
    assert main(["mesh", str(shape_file), "-o", str(tmp_path / "x.3mf"), "--colours", "17"]) == 3
    assert main(["mesh", str(shape_file), "-o", str(tmp_path / "x.glb"), "--pitch", "-1"]) == 3
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 4 and all(line.startswith("voxfab: error:") for line in err)
    assert "--colours: expected an integer number of filaments from 1 to 16, got 17" in err[2]
    assert main(["mesh", str(shape_file), "-o", str(tmp_path / "x.glb"), "--pitch", "1", "--size", "3"]) == 3
    assert "give one of them" in capsys.readouterr().err
