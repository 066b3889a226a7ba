"""The ``mesh`` recipe output: registered, typed options, files inside outdir."""

import json
import typing

import pytest

from voxfab.fabricate import get_output
from voxfab.fabricate.mesh import read_mesh, recipe_output
from voxfab.shape import VoxelShape, examples


def test_registered_and_hints_resolve():
    assert get_output("mesh") is recipe_output
    hints = typing.get_type_hints(recipe_output)
    assert typing.get_args(hints["format"]) == ("3mf", "stl", "obj", "glb")
    assert hints["size"] == float | None


@pytest.mark.parametrize("fmt", ["3mf", "stl"])
def test_writes_the_mesh_and_its_figures(tmp_path, fmt):
    shape = VoxelShape(examples.tunnel_cube(5), pitch=2.0)
    files = recipe_output(shape, tmp_path, name="tunnel", seed=0, format=fmt)
    assert [f.path for f in files] == [f"mesh.{fmt}", "mesh.json"]
    assert "3D printer" in files[0].purpose or "slicer" in files[0].purpose
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(f.path for f in files)
    figures = json.loads((tmp_path / "mesh.json").read_text())
    assert figures["volume_mm3"] == pytest.approx(81 * 8.0)
    assert figures["size_mm"] == [10.0, 10.0, 10.0]
    back = read_mesh(tmp_path / f"mesh.{fmt}")
    assert len(back.triangles) == figures["triangles"]


def test_size_option_scales_the_longest_side(tmp_path):
    shape = VoxelShape(examples.box(2, 4, 8), pitch=1.0)
    recipe_output(shape, tmp_path, name="bar", seed=0, size=40.0, format="obj")
    figures = json.loads((tmp_path / "mesh.json").read_text())
    assert figures["size_mm"] == [10.0, 20.0, 40.0] and figures["pitch_mm"] == 5.0


def test_same_inputs_same_bytes(tmp_path):
    shape = VoxelShape(examples.random_shape(2, side=8, fill=0.3), pitch=2.0)
    recipe_output(shape, tmp_path / "a", name="blob", seed=0)
    recipe_output(shape, tmp_path / "b", name="blob", seed=0)
    for name in ("mesh.3mf", "mesh.json"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
