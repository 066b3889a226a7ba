"""3D plates: STEP re-imports with the expected volume; STL matches it (build123d is slow: one shape)."""

from __future__ import annotations

import numpy as np
import pytest

from voxfab.fabricate.plates import make_slices, write_slices, write_step
from voxfab.shape import VoxelShape


def test_step_and_stl_of_the_plate_stack(tmp_path) -> None:
    bd = pytest.importorskip("build123d")
    trimesh = pytest.importorskip("trimesh")
    g = np.ones((3, 3, 2), dtype=bool)
    g[1, 1, 1] = False  # a voxel hole in the top layer
    result = make_slices(VoxelShape(g, 4.0), thickness=2.0, dowel=2.0, dowel_margin=0.5, sheet="100x100")
    stack = result.stack
    assert stack.plates_per_layer == 2 and len(stack.dowels) >= 1
    expected = sum(p.area * p.thickness for p in stack.plates)
    files = {f.path for f in write_slices(result, tmp_path, name="t", step=True)}
    assert {"plates.step", "plates.stl"} <= files
    write_step(stack, tmp_path / "again.step")
    assert (tmp_path / "plates.step").read_bytes() == (tmp_path / "again.step").read_bytes()
    back = bd.import_step(tmp_path / "plates.step")
    assert len(back.solids()) == len(stack.plates)
    assert back.volume == pytest.approx(expected, rel=1e-6)
    # plates sit on top of each other: 4 plates of 2 mm
    bb = back.bounding_box()
    assert bb.min.Z == pytest.approx(0.0, abs=1e-6) and bb.max.Z == pytest.approx(8.0, abs=1e-6)
    mesh = trimesh.load(tmp_path / "plates.stl")
    # tessellated dowel holes are polygons inscribed in the circles: slightly more material
    assert mesh.volume == pytest.approx(expected, rel=2e-3)
    assert mesh.volume >= expected - 1e-6
