"""assembly.3mf: every style's plates as assembled, read back with trimesh."""

from __future__ import annotations

import json

import numpy as np
import pytest
import trimesh
from _plate_checks import construction_shapes, manifold_of, voxel_solid

from voxfab.fabricate.plates import PlateOptions, fabricate_plates


@pytest.fixture(scope="module")
def shapes():
    return construction_shapes()


def test_stacked_style_writes_its_assembly_too(shapes, tmp_path) -> None:
    shape = shapes["overhang"]
    fabricate_plates(shape, PlateOptions(thickness=4.0), tmp_path / "s", name="o")
    report = json.loads((tmp_path / "s" / "plates.json").read_text())
    scene = trimesh.load(tmp_path / "s" / "assembly.3mf", process=False, force="scene")
    assert sorted(scene.geometry) == sorted(p["label"] for p in report["plates_list"])
    solid = voxel_solid(shape)
    for p in report["plates_list"]:
        mesh = scene.geometry[p["label"]]
        z = np.asarray(mesh.vertices)[:, 2]
        assert (z.min(), z.max()) == pytest.approx((p["z"], p["z"] + 4.0))
        # dowel holes are 64-gons in the solid and exact circles in the report
        assert mesh.volume == pytest.approx(p["area"] * 4.0, rel=2e-3)
        assert (manifold_of(mesh) - solid).volume() < 1e-3
