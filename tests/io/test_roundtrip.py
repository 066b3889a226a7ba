"""Every writable format round-trips voxel-exact (hypothesis property tests)."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from voxfab import io

WRITABLE = [".npy", ".npz", ".txt", ".vox", ".binvox"]


def test_registry_lists_the_formats():
    assert io.writable_formats() == sorted([*WRITABLE, "/"])
    assert set(io.readable_formats()) == set(WRITABLE) | {"/", ".png", ".stl", ".obj", ".ply", ".3mf", ".glb"}


@st.composite
def grids(draw):
    """Random grids, one side up to 256, with empty margins or edge voxels."""
    big_axis = draw(st.integers(0, 2))
    shape = [draw(st.integers(1, 9)) for _ in range(3)]
    shape[big_axis] = draw(st.one_of(st.integers(1, 40), st.integers(200, 256)))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    density = draw(st.sampled_from([0.02, 0.3, 0.9, 1.0]))
    grid = rng.random(shape) < density
    if draw(st.booleans()):
        # empty margins: content well inside the grid, edges empty
        grid[0], grid[-1] = False, False
        grid[:, 0], grid[:, -1] = False, False
        grid[:, :, 0], grid[:, :, -1] = False, False
    else:
        # the far corner is filled: the largest coordinate must survive
        grid[-1, -1, -1] = True
    if not grid.any():
        grid[tuple(s // 2 for s in shape)] = True
    return grid


def _corner_256() -> np.ndarray:
    g = np.zeros((256, 1, 2), dtype=bool)
    g[255, 0, 1] = g[0, 0, 0] = True
    return g


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(grid=grids())
@example(grid=_corner_256())
@example(grid=np.ones((1, 1, 1), dtype=bool))
@example(grid=np.ones((3, 256, 2), dtype=bool))
@pytest.mark.parametrize("ext", WRITABLE)
def test_round_trip_voxel_exact(ext, grid):
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"shape{ext}"
        io.write(grid, path)
        result = io.read(path)
        assert result.grid.dtype == bool
        assert result.grid.shape == grid.shape
        assert np.array_equal(result.grid, grid)
        assert result.notes == ()
        # writing again gives the same bytes
        again = Path(tmp) / f"again{ext}"
        io.write(result.grid, again)
        assert again.read_bytes() == path.read_bytes()


@pytest.mark.parametrize("ext", WRITABLE)
def test_over_256_refused_and_nothing_written(tmp_path, ext):
    from voxfab.errors import InvalidShapeError

    with pytest.raises(InvalidShapeError, match="over the limit of 256"):
        io.write(np.ones((2, 257, 1), dtype=bool), tmp_path / f"x{ext}")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("ext", WRITABLE)
def test_empty_grid_refused(tmp_path, ext):
    from voxfab.errors import InvalidShapeError

    with pytest.raises(InvalidShapeError, match="empty"):
        io.write(np.zeros((2, 2, 2), dtype=bool), tmp_path / f"x{ext}")


def test_unknown_extensions(tmp_path):
    from voxfab.errors import UnknownFormatError

    (tmp_path / "a.xyz").write_text("hello")
    with pytest.raises(UnknownFormatError, match=r"a.xyz: unknown extension '.xyz'; readable: .3mf, .binvox, .+, a folder of PNG slices"):
        io.read(tmp_path / "a.xyz")
    with pytest.raises(UnknownFormatError, match=r"cannot write '.stl'; writable: .binvox"):
        io.write(np.ones((1, 1, 1), bool), tmp_path / "a.stl")
    with pytest.raises(UnknownFormatError, match="no extension"):
        io.write(np.ones((1, 1, 1), bool), tmp_path / "plain")
