"""Sheet writers (DXF R2000 and R12, SVG) and the assembly PDF: audits, read-backs, determinism."""

from __future__ import annotations

import math
import re

import ezdxf
import numpy as np
import pytest
from _dxf_read import closed_rings, polylines
from lxml import etree

from voxfab.fabricate.plates import (
    assembly_pdf,
    make_slices,
    sheet_dxf,
    sheet_svg,
    write_dxf,
    write_svg,
)
from voxfab.shape import VoxelShape, examples


@pytest.fixture(scope="module")
def result():
    return make_slices(VoxelShape(examples.vase(10), 3.0), sheet="60x50", thickness=3.0)


def _signed_area(xy: np.ndarray) -> float:
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


@pytest.mark.parametrize(("version", "code"), [("R2000", "AC1015"), ("R12", "AC1009")])
def test_dxf_audits_clean_and_reads_back_the_geometry(result, tmp_path, version, code) -> None:
    assert len(result.sheets) >= 2
    for sheet in result.sheets:
        path = tmp_path / f"s{sheet.index}.dxf"
        write_dxf(sheet, path, version=version)
        doc = ezdxf.readfile(path)
        assert doc.dxfversion == code
        auditor = doc.audit()
        assert not auditor.has_errors and not auditor.has_fixes
        assert {"CUT", "SCORE", "LABEL"} <= {layer.dxf.name for layer in doc.layers}
        assert doc.layers.get("CUT").dxf.color == 1 and doc.layers.get("SCORE").dxf.color == 5
        msp = doc.modelspace()
        cut = closed_rings(doc)
        # the extents header holds the geometry
        x0, y0, _ = doc.header["$EXTMIN"]
        x1, y1, _ = doc.header["$EXTMAX"]
        allpts = np.concatenate(cut)
        assert (x0, y0) == pytest.approx(tuple(allpts.min(axis=0)), abs=1e-3)
        assert (x1, y1) == pytest.approx(tuple(allpts.max(axis=0)), abs=1e-3)
        circles = list(msp.query("CIRCLE"))
        assert len(cut) == len([e for e in polylines(doc, "CUT")]) == sum(len(p.cut) for p in sheet.parts)
        assert len(circles) == sum(len(p.circles) for p in sheet.parts)
        # signed ring areas (holes are clockwise) minus the dowel circles = material
        area = sum(_signed_area(ring) for ring in cut)
        area -= sum(math.pi * c.dxf.radius**2 for c in circles)
        assert area == pytest.approx(sheet.material_area, rel=1e-9)
        # two-point strokes are written as LINEs
        for layer, strokes in (("SCORE", "score"), ("LABEL", "engrave")):
            assert len(list(polylines(doc, layer))) == sum(len(getattr(p, strokes)) for p in sheet.parts)
        # every vertex lies on the sheet
        pts = np.concatenate([pts for _, pts, _ in polylines(doc)])
        assert pts.min() >= 0 and (pts <= (sheet.width, sheet.height)).all()


def test_dxf_and_svg_are_byte_identical_for_equal_inputs(result) -> None:
    again = make_slices(VoxelShape(examples.vase(10), 3.0), sheet="60x50", thickness=3.0)
    for a, b in zip(result.sheets, again.sheets):
        assert sheet_dxf(a) == sheet_dxf(b)
        assert sheet_svg(a) == sheet_svg(b)


def test_svg_is_in_mm_with_flipped_y(result, tmp_path) -> None:
    sheet = result.sheets[0]
    path = tmp_path / "s.svg"
    write_svg(sheet, path)
    root = etree.parse(str(path)).getroot()
    assert root.get("width") == "60mm" and root.get("height") == "50mm"
    assert root.get("viewBox") == "0 0 60 50"
    ns = {"s": "http://www.w3.org/2000/svg"}
    groups = {g.get("id"): g for g in root.findall("s:g", ns)}
    assert groups["CUT"].get("stroke") == "#ff0000" and groups["SCORE"].get("stroke") == "#0000ff"
    assert groups["CUT"].get("stroke-width") == "0.01"
    paths = groups["CUT"].findall("s:path", ns)
    assert len(paths) == sum(len(p.cut) for p in sheet.parts)
    assert len(groups["CUT"].findall("s:circle", ns)) == sum(len(p.circles) for p in sheet.parts)
    first = re.match(r"M([^,]+),(\S+)", paths[0].get("d"))
    x, y = sheet.parts[0].cut[0][0]
    assert float(first.group(1)) == pytest.approx(x, abs=1e-4)
    assert float(first.group(2)) == pytest.approx(sheet.height - y, abs=1e-4)


def test_assembly_pdf_is_deterministic_with_a_page_per_25_layers() -> None:
    tall = make_slices(VoxelShape(examples.box(1, 1, 26), 2.0), thickness=2.0, dowel=0)
    a = assembly_pdf(tall.stack, title="tower")
    assert a.startswith(b"%PDF")
    assert a == assembly_pdf(tall.stack, title="tower")
    assert len(re.findall(rb"/Type /Page\b", a)) == 2
    assert b"CreationDate" not in a
