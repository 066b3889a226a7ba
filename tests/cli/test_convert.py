"""``voxfab convert`` through the real entry point."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
import trimesh

from voxfab import io
from voxfab.cli import main
from voxfab.shape import examples


def voxfab(*args: str, cwd=None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "voxfab", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=120)


def test_mesh_to_vox_with_resolution_prints_notes(tmp_path):
    trimesh.creation.icosphere(subdivisions=3, radius=3.0).export(tmp_path / "ball.stl")
    proc = voxfab("convert", tmp_path / "ball.stl", tmp_path / "ball.vox", "--resolution", "12")
    assert proc.returncode == 0, proc.stderr
    assert "voxfab: note: mesh of 1280 triangles, watertight" in proc.stderr
    assert "voxfab: note: voxelized at 12 voxels along the longest side (0.5 mesh units per voxel)" in proc.stderr
    grid = io.read(tmp_path / "ball.vox").grid
    assert grid.shape == (12, 12, 12)
    assert proc.stdout.strip() == f"{tmp_path / 'ball.vox'}: 12x12x12 grid, {grid.sum()} voxels"
    # the centre column is full height, the corners are empty
    assert grid[5:7, 5:7, :].all() and not grid[0, 0, :].any()


def test_chain_of_conversions_is_voxel_exact(tmp_path):
    grid = examples.vase()
    io.write(grid, tmp_path / "a.npy")
    chain = ["a.npy", "b.vox", "c.binvox", "d.txt", "e.npz", "f.npy"]
    for src, dst in zip(chain, chain[1:]):
        assert main(["convert", str(tmp_path / src), str(tmp_path / dst)]) == 0
    assert np.array_equal(io.read(tmp_path / "f.npy").grid, grid)


def test_png_folder_with_threshold(tmp_path, capsys):
    from PIL import Image

    folder = tmp_path / "slices"
    folder.mkdir()
    for z in range(3):
        Image.fromarray(np.full((2, 4), 100 + 50 * z, dtype=np.uint8), "L").save(folder / f"z{z}.png")
    assert main(["convert", str(folder), str(tmp_path / "s.npy"), "--threshold", "175"]) == 0
    grid = io.read(tmp_path / "s.npy").grid
    assert grid.shape == (4, 2, 3) and grid[:, :, :2].all() and not grid[:, :, 2].any()


def test_corrupt_input_is_one_line_error_and_nothing_written(tmp_path):
    good = tmp_path / "good.vox"
    io.write(examples.ball(3), good)
    bad = tmp_path / "bad.vox"
    bad.write_bytes(good.read_bytes()[:-100])
    proc = voxfab("convert", bad, tmp_path / "out.npy")
    assert proc.returncode == 5
    assert proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"voxfab: error: {bad}: ")
    assert "truncated" in lines[0] and "Traceback" not in proc.stderr
    assert not (tmp_path / "out.npy").exists()


def test_debug_shows_the_traceback(tmp_path):
    (tmp_path / "bad.binvox").write_bytes(b"garbage")
    proc = voxfab("--debug", "convert", tmp_path / "bad.binvox", tmp_path / "out.npy")
    assert proc.returncode == 5
    assert "Traceback" in proc.stderr and proc.stderr.strip().splitlines()[-1].startswith("voxfab: error:")


@pytest.mark.parametrize(
    ("setup", "args", "code", "message"),
    [
        ("ball.npy", ["ball.npy", "out.stl"], 4, "out.stl: cannot write '.stl'"),
        ("ball.npy", ["ball.xyz", "out.npy"], 4, "unknown extension '.xyz'"),
        ("ball.npy", ["missing.vox", "out.npy"], 5, "missing.vox: no such file"),
        ("ball.npy", ["ball.npy", "out.vox", "--resolution", "10"], 3, "option resolution does not apply to .npy"),
        ("big.npy", ["big.npy", "out.vox"], 3, "over the limit of 256 voxels per side"),
        ("empty.npy", ["empty.npy", "out.vox"], 3, "empty"),
        ("ints.npy", ["ints.npy", "out.vox"], 3, "only 0 and 1 values"),
    ],
)
def test_bad_input_exit_codes(tmp_path, capsys, setup, args, code, message):
    arrays = {
        "ball.npy": examples.ball(2),
        "big.npy": np.ones((300, 1, 1), dtype=bool),
        "empty.npy": np.zeros((3, 3, 3), dtype=bool),
        "ints.npy": np.full((2, 2, 2), 7, dtype=np.int16),
    }
    np.save(tmp_path / setup, arrays[setup])
    (tmp_path / "ball.xyz").write_text("x")
    argv = ["convert", *(str(tmp_path / a) if not a.startswith("-") and not a.isdigit() else a for a in args)]
    assert main(argv) == code
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("voxfab: error: ") and message in err
    assert not (tmp_path / "out.vox").exists() and not (tmp_path / "out.npy").exists()
