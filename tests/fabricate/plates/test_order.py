"""The assembly order of slotted plates: steps in plates.json and the one-page PDF."""

from __future__ import annotations

import json
import re

import pytest
from _plate_checks import construction_shapes

from voxfab.fabricate.plates import PlateOptions, fabricate_plates


@pytest.fixture(scope="module")
def shapes():
    return construction_shapes()


@pytest.mark.parametrize("style", ["interlocked", "radial"])
def test_assembly_order_lowers_every_plate_onto_plates_already_in_place(shapes, tmp_path, style) -> None:
    """The steps name every plate once; a plate's lower slots hold plates of earlier steps only."""
    fabricate_plates(shapes["queen"], PlateOptions(style=style), tmp_path / "s", name="queen")
    report = json.loads((tmp_path / "s" / "plates.json").read_text())
    step_of: dict[str, int] = {}
    for k, step in enumerate(report["steps"]):
        for label in re.findall(r"\b[ABR]\d+(?:-\d+)?\b", step.split(":")[0]):
            step_of.setdefault(label, k)
    assert sorted(step_of) == sorted(p["label"] for p in report["plates_list"])
    for p in report["plates_list"]:
        for s in p["slots"]:
            # a slot from the bottom goes over a plate already standing, one from the top takes a later one
            if s["side"] == "bottom":
                assert step_of[s["partner"]] < step_of[p["label"]]
            else:
                assert step_of[s["partner"]] > step_of[p["label"]]
    pdf = (tmp_path / "s" / "assembly.pdf").read_bytes()
    assert pdf.startswith(b"%PDF") and pdf.count(b"/Type /Page") - pdf.count(b"/Type /Pages") == 1


@pytest.mark.parametrize(("name", "pitch"), [("queen", 3.4), ("knight", 2.8)])
def test_plan_labels_never_overprint_and_partner_labels_stand_upright_at_full_size(name, pitch) -> None:
    """The plan names every bar clear of the other labels and bars; on the plates, partner labels are engraved
    at the plate label's full size, the right way up, but for the few on plates with no such room left."""
    import numpy as np
    import shapely

    import voxfab.fabricate.plates._slotted as slotted
    from voxfab.fabricate.plates._labels import full_height
    from voxfab.fabricate.plates._order import construction_drawing, plan_label_boxes
    from voxfab.recipe import load_recipe, make_shape

    grid = make_shape(load_recipe(f"recipes/chess/{name}.toml")).grid
    marks = []
    place = slotted.place_label

    def record(text, *args, **kwargs):  # every placement made, with what it was asked for
        got = place(text, *args, **kwargs)
        if got is not None and text.startswith("("):
            marks.append((got, args[0]))
        return got

    slotted.place_label = record
    try:
        construction = slotted.make_interlocked(grid, pitch=pitch)
    finally:
        slotted.place_label = place
    full = full_height(pitch)
    upright = [m for m, _ in marks if not m.turned and m.height == pytest.approx(full)]
    assert len(upright) >= 0.85 * len(marks), [(m.text, m.height, m.turned) for m, _ in marks]

    page = construction_drawing(construction, title=name).pages[0]
    cut = page.layers["CUT"]
    rings = [cut.points[a:b] for a, b in zip(cut.offsets[:-1], cut.offsets[1:])]
    texts = [p.label.text for p in construction.plates]
    boxes = [shapely.box(*b) for b in plan_label_boxes(rings, texts)]
    bars = [shapely.Polygon(r) for r in rings]
    assert len(boxes) == len(construction.plates)
    for i, a in enumerate(boxes):
        assert not any(a.intersects(b) for b in boxes[i + 1:]), texts[i]
        assert not any(a.intersects(bar) for j, bar in enumerate(bars) if j != i), texts[i]
    label = page.layers["LABEL"]
    points = shapely.points(np.asarray(label.points))
    for box, text in zip(boxes, texts):
        assert shapely.contains(box.buffer(0.05), points).sum() >= 2 * len(text), text
