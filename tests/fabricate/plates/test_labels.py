"""Plate labels are engraved whole and at least 2 mm tall, or not at all and named on the assembly plan."""

from __future__ import annotations

import json

import ezdxf
import numpy as np
import pytest
import shapely
from _dxf_read import closed_rings, polylines
from _plate_checks import draws_text, pdf_polylines

from voxfab.fabricate.plates import PlateOptions, fabricate_plates, text_strokes
from voxfab.recipe import load_recipe, make_shape

#: The smallest label the nets engrave, mm: plate labels are no smaller.
SMALLEST = 2.0


def _parts_and_labels(folder, sheets: int) -> list[tuple[shapely.Polygon, list[np.ndarray]]]:
    """Each part cut on the sheets (outer CUT ring less the rings inside it) with the LABEL strokes on it."""
    out = []
    for k in range(1, sheets + 1):
        doc = ezdxf.readfile(folder / f"sheet-{k:02d}.dxf")
        rings = sorted((shapely.Polygon(r) for r in closed_rings(doc)), key=lambda r: -r.area)
        parts: list[shapely.Polygon] = []
        for r in rings:
            host = [i for i, p in enumerate(parts) if p.contains(r)]
            if host:
                parts[host[-1]] = parts[host[-1]].difference(r)
            else:
                parts.append(r)
        strokes = [pts for _, pts, _ in polylines(doc, "LABEL")]
        for p in parts:
            out.append((p, [s for s in strokes if p.contains(shapely.LineString(s) if len(s) > 1 else
                                                              shapely.Point(s[0]))]))
        assert sum(len(s) for _, s in out[-len(parts):]) == len(strokes)  # no stroke off its part
    return out


@pytest.mark.parametrize(("recipe", "small"), [("king", {"25-1.1", "25-1.2"}), ("pawn", set())])
def test_labels_are_whole_and_2_mm_tall_or_named_on_the_plan(tmp_path, recipe, small) -> None:
    """The king at 3.8 mm: its 3.8 mm top plates are too small for "25-1.1" whole at 2 mm; the pawn at 2 mm."""
    shape = make_shape(load_recipe(f"recipes/chess/{recipe}.toml"))
    made = fabricate_plates(shape, PlateOptions(), tmp_path / recipe, name=recipe)
    report = json.loads((tmp_path / recipe / "plates.json").read_text())
    on_plan = set(report.get("labels_on_plan", ()))
    engraved = [p["label"] for p in report["plates_list"] if p["label"] not in on_plan]
    parts = _parts_and_labels(tmp_path / recipe, report["sheets"])
    assert len(parts) == report["plates"]
    # every engraved label whole: as many strokes as the font draws it with (a clipped one loses some)
    assert sum(len(s) for _, s in parts) == sum(len(text_strokes(t, 1.0)) for t in engraved)
    assert sum(not s for _, s in parts) == len(on_plan)
    for _, strokes in parts:
        if strokes:  # the glyphs' height, whichever way the label reads
            pts = np.concatenate(strokes)
            assert min(np.ptp(pts[:, 0]), np.ptp(pts[:, 1])) >= SMALLEST - 1e-3
    assert small <= on_plan
    # the unengraved plates are named on the plan, and in the warnings
    page = pdf_polylines(tmp_path / recipe / "assembly.pdf")[0]
    assert not draws_text(page, "25-1.3")
    for name in on_plan:
        assert draws_text(page, name), name
        assert any(name in w for w in made.warnings)
