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
