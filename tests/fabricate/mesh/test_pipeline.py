"""The print pipeline ``fabricate_mesh`` and its options: checked values, files inside outdir."""

import json

import pytest

from voxfab._shared.options import OptionError
from voxfab.fabricate.mesh import MeshOptions, fabricate_mesh, read_mesh
from voxfab.shape import VoxelShape, examples


def _run(shape, folder, name, **options):
    o = MeshOptions(**options)
    return fabricate_mesh(shape, o, folder / f"mesh.{o.format}", name=name, report_path=folder / "mesh.json")


def test_options_are_checked_when_made():
    assert MeshOptions().format == "3mf" and MeshOptions(size=40).size == 40.0
    for bad in ({"format": "step"}, {"size": 0}, {"size": float("inf")}, {"hollow": -1}, {"magnet": "6"},
                {"label": "  "}, {"contacts": "glue"}, {"solid": 1}):
        with pytest.raises(OptionError):
            MeshOptions(**bad)


@pytest.mark.parametrize("fmt", ["3mf", "stl"])
def test_writes_the_mesh_and_its_figures(tmp_path, fmt):
    shape = VoxelShape(examples.tunnel_cube(5), pitch=2.0)
    made = _run(shape, tmp_path, "tunnel", format=fmt)
    files = made.files
    assert [f.path for f in files] == [f"mesh.{fmt}", "mesh.json"]
    assert "3D printer" in files[0].purpose or "slicer" in files[0].purpose
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(f.path for f in files)
    figures = json.loads((tmp_path / "mesh.json").read_text())
    assert figures == made.report and made.warnings == ()
    assert figures["volume_mm3"] == pytest.approx(81 * 8.0)
    assert figures["size_mm"] == [10.0, 10.0, 10.0]
    back = read_mesh(tmp_path / f"mesh.{fmt}")
    assert len(back.triangles) == figures["triangles"]


def test_size_option_scales_the_longest_side(tmp_path):
    shape = VoxelShape(examples.box(2, 4, 8), pitch=1.0)
    _run(shape, tmp_path, "bar", size=40.0, format="obj")
    figures = json.loads((tmp_path / "mesh.json").read_text())
    assert figures["size_mm"] == [10.0, 20.0, 40.0] and figures["pitch_mm"] == 5.0


def test_same_inputs_same_bytes(tmp_path):
    shape = VoxelShape(examples.random_shape(2, side=8, fill=0.3), pitch=2.0)
    _run(shape, tmp_path / "a", "blob")
    _run(shape, tmp_path / "b", "blob")
    for name in ("mesh.3mf", "mesh.json"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
