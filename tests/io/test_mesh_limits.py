"""Mesh size limits: checked before parsing (bytes, stated triangles) and before voxelizing (work)."""

from __future__ import annotations

import time

import numpy as np
import pytest
import trimesh

from voxfab import io
from voxfab.errors import LimitError, VoxfabError
from voxfab.io.mesh import ray_tests


def slivers(n: int) -> trimesh.Trimesh:
    """``n`` long thin triangles lying across the unit cube: few triangles, much voxelizing work."""
    rng = np.random.default_rng(0)
    a = rng.random((n, 3))
    v = np.stack([a, 1 - a, a + 1e-4], axis=1).reshape(-1, 3)
    return trimesh.Trimesh(v, np.arange(3 * n).reshape(-1, 3), process=False)


def test_ray_tests_count_the_columns_each_triangle_covers():
    # One triangle spanning the whole grid diagonally covers every column on each axis.
    v = np.array([[0.0, 0, 0], [1, 1, 0], [0, 1, 1]])
    assert ray_tests(v, [[0, 1, 2]], resolution=4) == 3 * 5 * 5
    ball = trimesh.creation.icosphere(subdivisions=3)
    assert ray_tests(ball.vertices, ball.faces, resolution=25) < 10 * len(ball.faces)


def test_long_thin_triangles_are_refused_before_voxelizing(tmp_path):
    slivers(2000).export(tmp_path / "slivers.stl")
    start = time.perf_counter()
    with pytest.raises(LimitError, match=r"resolution 256 takes [\d,]+ triangle-column tests, over the limit of 60,000,000"):
        io.read(tmp_path / "slivers.stl", resolution=256)
    assert time.perf_counter() - start < 10
    # At the default resolution the same mesh is cheap and reads.
    assert io.read(tmp_path / "slivers.stl").grid.any()


PLY_TETRAHEDRON = (
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face {faces}\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n"
)


@pytest.mark.parametrize(("faces", "error"), [
    ("1000000000", "over the limit of 1,000,000"),
    ("6", "states 6 faces but the file holds 4"),
    ("many", "is not a number"),
])
def test_a_ply_header_that_lies_about_its_faces_is_refused(tmp_path, faces, error):
    path = tmp_path / "t.ply"
    path.write_text(PLY_TETRAHEDRON.format(faces=faces))
    with pytest.raises(VoxfabError, match=error):
        io.read(path)


def test_a_ply_header_that_tells_the_truth_is_read(tmp_path):
    path = tmp_path / "t.ply"
    path.write_text(PLY_TETRAHEDRON.format(faces=4))
    assert io.read(path).grid.any()
