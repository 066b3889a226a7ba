""".binvox: hand-made files per the spec, and trimesh's reader and encoder as a check."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab import io
from voxfab.errors import FormatError, InvalidShapeError
from voxfab.io.binvox import binvox_bytes
from voxfab.shape import examples


def runs(*pairs: tuple[int, int]) -> bytes:
    return bytes(b for pair in pairs for b in pair)


def header(dims: tuple[int, int, int], extra: str = "") -> bytes:
    return f"#binvox 1\ndim {dims[0]} {dims[1]} {dims[2]}\n{extra}translate 0 0 0\nscale 1\ndata\n".encode()


def test_hand_made_file_uses_x_z_y_order(tmp_path):
    # 2 x 3 x 4 grid; runs in x-z-y order, y fastest: index = x*12 + z*3 + y.
    # Voxel (x=1, y=2, z=3) is index 12 + 9 + 2 = 23, the last one.
    # Voxel (x=0, y=1, z=0) is index 1.
    path = tmp_path / "hand.binvox"
    path.write_bytes(header((2, 3, 4)) + runs((0, 1), (1, 1), (0, 21), (1, 1)))
    grid = io.read(path).grid
    assert grid.shape == (2, 3, 4)
    assert sorted(map(tuple, np.argwhere(grid).tolist())) == [(0, 1, 0), (1, 2, 3)]


def test_written_file_read_by_hand(tmp_path):
    grid = np.zeros((2, 3, 4), dtype=bool)
    grid[0, 1, 0] = grid[1, 2, 3] = True
    io.write(grid, tmp_path / "a.binvox")
    data = (tmp_path / "a.binvox").read_bytes()
    head, body = data.split(b"data\n", 1)
    assert head.splitlines()[:2] == [b"#binvox 1", b"dim 2 3 4"]
    assert body == runs((0, 1), (1, 1), (0, 21), (1, 1))


def test_long_runs_are_split_at_255(tmp_path):
    grid = np.ones((10, 10, 10), dtype=bool)
    grid[0, 0, 0] = False
    body = binvox_bytes(grid).split(b"data\n", 1)[1]
    assert body == runs((0, 1), (1, 255), (1, 255), (1, 255), (1, 234))
    io.write(grid, tmp_path / "a.binvox")
    assert np.array_equal(io.read(tmp_path / "a.binvox").grid, grid)


@pytest.mark.parametrize("make", [examples.vase, lambda: examples.torus(6, 2), lambda: examples.tunnel_cube(5)])
def test_round_trip(tmp_path, make):
    grid = make()
    io.write(grid, tmp_path / "s.binvox")
    assert np.array_equal(io.read(tmp_path / "s.binvox").grid, grid)


def test_trimesh_reads_our_files_as_the_same_grid(tmp_path):
    import trimesh

    rng = np.random.default_rng(3)
    grid = rng.random((12, 12, 12)) < 0.3  # trimesh's loader handles cubic grids only
    io.write(grid, tmp_path / "a.binvox")
    loaded = trimesh.load(tmp_path / "a.binvox")
    assert np.array_equal(np.asarray(loaded.matrix), grid)


@pytest.mark.parametrize("shape", [(5, 7, 9), (40, 3, 17), (256, 1, 2)])
def test_runs_equal_trimesh_encoding(shape):
    from trimesh.exchange.binvox import binvox_bytes as trimesh_binvox_bytes
    from trimesh.voxel.encoding import DenseEncoding

    rng = np.random.default_rng(sum(shape))
    grid = rng.random(shape) < 0.4
    grid[:, :, : shape[2] // 2] = False  # long runs too
    rle = DenseEncoding(grid.transpose(0, 2, 1)).flat.run_length_data(dtype=np.uint8)
    theirs = trimesh_binvox_bytes(rle, shape=grid.shape)
    assert theirs.split(b"data\n", 1)[1] == binvox_bytes(grid).split(b"data\n", 1)[1]
    assert b"dim %d %d %d" % shape in theirs


def test_trimesh_written_file_is_read(tmp_path):
    import trimesh
    from trimesh.voxel import VoxelGrid

    grid = examples.ball(4)
    (tmp_path / "t.binvox").write_bytes(trimesh.exchange.binvox.export_binvox(VoxelGrid(grid)))
    assert np.array_equal(io.read(tmp_path / "t.binvox").grid, grid)


def test_header_with_comments_and_any_key_order(tmp_path):
    path = tmp_path / "c.binvox"
    path.write_bytes(b"#binvox 1\n# made by hand\nscale 2.5\ndim 1 1 2\ntranslate -1 0.5 3\ndata\n" + runs((1, 2)))
    assert io.read(path).grid.tolist() == [[[True, True]]]


@pytest.mark.parametrize(
    ("data", "error", "message"),
    [
        (b"#binvox 1\ndata\n" + runs((1, 1)), FormatError, "no 'dim'"),
        (b"#binvox 1\ndim 2 2\ndata\n", FormatError, "not valid"),
        (b"#binvox 1\ndim 1 1 1\nscale nan\ndata\n" + runs((1, 1)), FormatError, "not valid"),
        (b"#binvox 1\ndim 1 1 1\ncolour red\ndata\n" + runs((1, 1)), FormatError, "not valid"),
        (b"#binvox 1\ndim 0 1 1\ndata\n", FormatError, "below 1"),
        (b"#binvox 1\ndim 1 1 1\n", FormatError, "header"),
        (b"#binvox one\ndim 1 1 1\ndata\n" + runs((1, 1)), FormatError, "not a binvox file"),
        (header((2, 2, 2)) + runs((1, 8))[:-1], FormatError, "odd number"),
        (header((2, 2, 2)) + runs((1, 5)), FormatError, "truncated"),
        (header((2, 2, 2)) + runs((1, 8), (0, 1)), FormatError, "cover 9 voxels"),
        (header((2, 2, 2)) + runs((2, 8)), FormatError, "not 0 or 1"),
        (header((257, 1, 1)) + runs((1, 255), (1, 2)), InvalidShapeError, "over the limit of 256"),
        (header((1, 1, 1)) + runs((0, 1)), InvalidShapeError, "empty"),
    ],
)
def test_bad_files(tmp_path, data, error, message):
    path = tmp_path / "bad.binvox"
    path.write_bytes(data)
    with pytest.raises(error, match=message) as info:
        io.read(path)
    assert str(path) in str(info.value)
