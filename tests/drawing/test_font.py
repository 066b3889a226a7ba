"""The single-stroke font of the net drawings: complete, inside its box, and legible at 5 mm."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import shapely

from voxfab.drawing._font import CAP_HEIGHT, GLYPHS, glyph_for, text_polylines, text_width

REQUIRED = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.-"


def glyph_shape(text: str, height: float = 5.0):
    lines = text_polylines([text], [(0.0, 0.0)], [(1.0, 0.0)], height, center=True)
    geoms = [shapely.LineString(x) if len(x) > 1 and np.ptp(x, axis=0).any() else shapely.Point(x[0])
             for x in lines.lines()]
    # A 0.3 mm pen or laser line.
    return shapely.union_all([g.buffer(0.15) for g in geoms])


def test_every_required_character_has_strokes_inside_its_box() -> None:
    for ch in REQUIRED:
        strokes = GLYPHS[ch]
        assert strokes, ch
        pts = np.concatenate(strokes)
        assert pts.min() >= 0.0 and pts[:, 0].max() <= 4.0 and pts[:, 1].max() <= CAP_HEIGHT, ch


def test_characters_are_distinct_at_5_mm() -> None:
    shapes = {ch: glyph_shape(ch) for ch in REQUIRED}
    for a, b in itertools.combinations(REQUIRED, 2):
        sa, sb = shapes[a], shapes[b]
        # At least a 1.5 mm stroke of a 0.3 mm pen tells any two characters apart.
        differ = sa.symmetric_difference(sb).area
        assert differ > 0.45, (a, b, differ)


def test_layout_scale_direction_and_fallbacks() -> None:
    assert glyph_for("a") == "A" and glyph_for("é") == "?" and glyph_for("7") == "7"
    assert text_width("123", 6.0) == pytest.approx(2 * 6.0 + 4.0)
    up = text_polylines(["11"], [(10.0, 20.0)], [(0.0, 1.0)], 3.0)
    # Reading upwards: the text grows along +y and its cap height along -x.
    assert up.points[:, 1].min() >= 20.0 and up.points[:, 1].max() <= 20.0 + text_width("11", 3.0)
    assert up.points[:, 0].max() <= 10.0 + 1e-9 and up.points[:, 0].min() == pytest.approx(10.0 - 3.0)
    many = text_polylines(["1", "22", ""], np.zeros((3, 2)), np.tile([1.0, 0.0], (3, 1)), [2.0, 4.0, 1.0])
    assert len(many) == len(GLYPHS["1"]) + 2 * len(GLYPHS["2"])
