"""The ``slices`` recipe output and the plates.json report."""

from __future__ import annotations

import json

import ezdxf
import numpy as np
import pytest

from voxfab._shared.options import OptionError
from voxfab.fabricate.plates import PlateOptions, PlatesReport, fabricate_plates, make_slices
from voxfab.shape import VoxelShape, examples


def recipe_output(shape, outdir, *, name, **options):
    made = fabricate_plates(shape, PlateOptions(**options), outdir / "slices", name=name)
    return [f"slices/{f.path}" for f in made.files]


def test_options_refuse_meaningless_values_before_any_work() -> None:
    for bad in ({"thickness": 0.0001}, {"dowel": 1000}, {"sheet": "1x1"}, {"sheet": "1e9x1e9"},
                {"sheet": "big"}, {"axis": "w"}, {"kerf": -1}, {"margin": float("nan")}):
        with pytest.raises(OptionError):
            PlateOptions(**bad)


def test_pipeline_refuses_a_file_and_a_foreign_folder(tmp_path) -> None:
    from voxfab.errors import VoxfabError

    shape = VoxelShape(examples.box(2, 2, 2), 3.0)
    (tmp_path / "file.vox").write_bytes(b"x")
    with pytest.raises(VoxfabError, match="not a folder"):
        fabricate_plates(shape, PlateOptions(), tmp_path / "file.vox", name="b")
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "thesis.txt").write_text("keep me")
    with pytest.raises(VoxfabError, match="holds files that are not an earlier output"):
        fabricate_plates(shape, PlateOptions(), tmp_path / "docs", name="b")
    assert (tmp_path / "file.vox").read_bytes() == b"x"


def test_recipe_output_writes_sheets_pdf_and_report(tmp_path) -> None:
    shape = VoxelShape(examples.tunnel_cube(9), 2.0)
    paths = recipe_output(shape, tmp_path, name="tunnel", thickness=2.1, sheet="100x80", kerf=0.1)
    assert all(p.startswith("slices/") for p in paths)
    for p in paths:
        assert (tmp_path / p).is_file()
    assert "slices/assembly.pdf" in paths and "slices/plates.json" in paths
    assert not any(p.endswith((".step", ".stl")) for p in paths)  # step=False by default
    report = json.loads((tmp_path / "slices/plates.json").read_text())
    assert report["format"] == "voxfab-plates/1" and report["name"] == "tunnel"
    n_sheets = report["sheets"]
    assert sum(p.endswith(".dxf") for p in paths) == n_sheets == sum(p.endswith(".svg") for p in paths)
    assert report["layers"] == 9
    assert report["plates"] == len(report["plates_list"]) == report["pieces"] > 9
    assert report["drift"] == pytest.approx(9 * 2.1 - 9 * 2.0)
    assert report["stack_height"] == pytest.approx(18.9)
    assert report["material_area"] == pytest.approx(sum(p["area"] for p in report["plates_list"]), abs=0.01)
    assert 0 < report["material_fraction"] < 1
    doc = ezdxf.readfile(tmp_path / "slices/sheet-01.dxf")
    assert not doc.audit().has_errors
    # same inputs, same bytes
    again = tmp_path / "again"
    recipe_output(shape, again, name="tunnel", thickness=2.1, sheet="100x80", kerf=0.1)
    for p in paths:
        assert (again / p).read_bytes() == (tmp_path / p).read_bytes()


def test_report_counts_and_is_frozen() -> None:
    result = make_slices(VoxelShape(examples.box(4, 4, 3), 3.0), thickness=1.0, sheet="100x100")
    r = result.report
    assert isinstance(r, PlatesReport)
    assert (r.layers, r.pieces, r.plates_per_layer, r.plates) == (3, 3, 3, 9)
    assert r.sheets == len(result.sheets) and r.dowels == len(result.stack.dowels) > 0
    assert r.drift == pytest.approx(0.0)
    assert r.sheet_area == pytest.approx(r.sheets * 100 * 100)
    with pytest.raises(AttributeError):
        r.plates = 1  # type: ignore[misc]


def test_warnings_name_what_a_maker_must_know() -> None:
    from voxfab.fabricate.plates import plate_warnings

    box = VoxelShape(examples.box(4, 4, 4), 3.0)
    assert plate_warnings(make_slices(box, thickness=3.0, sheet="100x100").report) == []
    drift = plate_warnings(make_slices(box, thickness=3.2, sheet="100x100").report)
    assert drift == ["the stack is 12.8 mm tall (4 plate layers of 3.2 mm), +0.8 mm from the object's 12 mm"]
    assert plate_warnings(make_slices(box, thickness=3.0, dowel=0.0, sheet="100x100").report) == [
        "plates without dowels (dowel = 0): align the stack by the scored outlines"]
    g = np.zeros((5, 5, 3), bool)
    g[:2, :2, :] = True
    g[4, 4, 1] = True  # a loose island in the middle layer
    islands = plate_warnings(make_slices(VoxelShape(g, 3.0), sheet="100x100").report)
    assert any(w.startswith("1 loose island(s) touch no plate above or below: 2-2") for w in islands), islands
