"""Sections left out come with ways out that keep them, each checked by making the construction with it."""

from __future__ import annotations

import dataclasses
import json
import re

import numpy as np
import pytest
import trimesh
from _plate_checks import bunny

from voxfab.fabricate.plates import PlateOptions, fabricate_plates


def _top(folder) -> float:
    """Height in mm the assembled plates reach, from assembly.3mf."""
    scene = trimesh.load(folder / "assembly.3mf", force="scene")
    return float(max(m.bounds[1][2] for m in scene.geometry.values()))


def test_the_bunny_s_ears_and_back_are_kept_by_the_way_offered(tmp_path) -> None:
    """Interlocked at 3 mm, the bunny loses 9 sections and stops at 91 of 108 mm; the way out the warning and
    plates.json offer keeps every section and reaches the top."""
    shape = bunny()
    made = fabricate_plates(shape, PlateOptions(style="interlocked"), tmp_path / "asked", name="bunny")
    report = json.loads((tmp_path / "asked" / "plates.json").read_text())
    height = report["size"][2]
    assert len(report["left_out"]) >= 5 and _top(tmp_path / "asked") < 0.9 * height
    (line,) = [w for w in made.warnings if "left out" in w]
    assert report["ways_to_keep"] and all(way in line for way in report["ways_to_keep"])
    for way in report["ways_to_keep"]:
        changes = {k.replace("-", "_"): v for k, v in re.findall(r"--([a-z-]+) ([0-9.]+)", way)}
        assert changes, way
        options = dataclasses.replace(PlateOptions(style="interlocked"),
                                      **{k: type(getattr(PlateOptions(), k))(float(v)) for k, v in changes.items()})
        fabricate_plates(shape, options, tmp_path / "way", name="bunny")
        kept = json.loads((tmp_path / "way" / "plates.json").read_text())
        assert kept["left_out"] == [] and kept["plates"] == int(re.search(r"checked: (\d+) plates", way).group(1))
        assert _top(tmp_path / "way") == pytest.approx(height, abs=1e-3)
        assert np.isclose(kept["size"][2], height)
