"""Seam labels: short, one per seam, and made of characters that no glance or half turn confuses."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import shapely

from voxfab.drawing import text_polylines
from voxfab.drawing._font import GLYPHS
from voxfab.fabricate.netdraw import DrawingOptions
from voxfab.fabricate.netdraw._labels import (
    LABEL_ALPHABET,
    label_length,
    label_number,
    seam_label,
    seam_labels,
)
from voxfab.fabricate.netdraw._legible import number_height, smallest_face_size


def glyph(text: str, *, turned: bool = False, height: float = 2.0):
    """A label as drawn by a 0.3 mm laser line, upright or turned half a turn about its middle."""
    lines = text_polylines([text], [(0.0, height if turned else 0.0)], [(-1.0, 0.0) if turned else (1.0, 0.0)],
                           height, center=True)
    return shapely.union_all([shapely.LineString(x).buffer(0.15) for x in lines.lines()])


def test_the_alphabet_has_a_glyph_for_each_character_and_no_look_alikes() -> None:
    assert len(set(LABEL_ALPHABET)) == len(LABEL_ALPHABET) == 25
    assert all(GLYPHS[c] for c in LABEL_ALPHABET)
    assert set(LABEL_ALPHABET).isdisjoint("OQIZSBGV9WT")


def test_no_label_character_passes_for_another_upright_or_turned() -> None:
    upright = {c: glyph(c) for c in LABEL_ALPHABET}
    turned = {c: glyph(c, turned=True) for c in LABEL_ALPHABET}
    for a, b in itertools.product(LABEL_ALPHABET, repeat=2):
        # At 2 mm, two characters are told apart by at least a 1 mm stroke of a 0.3 mm line (P and R
        # differ by the leg of the R).
        if a != b:
            assert upright[a].symmetric_difference(upright[b]).area > 0.3, (a, b)
            assert turned[a].symmetric_difference(upright[b]).area > 0.3, (a, "turned", b)
    # The check can fail: the 6 turned is the 9, left out.  (T is left out by eye: the 1 turned, its
    # base bar on top, reads as a T though its tick keeps it just over the bar.)
    assert glyph("6", turned=True).symmetric_difference(glyph("9")).area < 1e-6


@pytest.mark.parametrize(("seams", "chars"), [(1, 1), (25, 1), (26, 2), (625, 2), (626, 3), (4182, 3),
                                              (15625, 3), (15626, 4)])
def test_label_length_is_the_shortest_that_tells_every_seam_apart(seams: int, chars: int) -> None:
    assert label_length(seams) == chars
    labels = seam_labels(range(1, seams + 1), chars)
    assert len(set(labels)) == seams and {len(x) for x in labels} == {chars}
    assert set("".join(labels)) <= set(LABEL_ALPHABET)


def test_labels_round_trip_and_refuse_what_they_cannot_say() -> None:
    rng = np.random.default_rng(3)
    for n in rng.integers(1, 25**3 + 1, size=200).tolist():
        assert label_number(seam_label(n, 3)) == n
    assert seam_label(1, 2) == "00" and seam_label(25, 2) == "0Y" and seam_label(26, 2) == "10"
    with pytest.raises(ValueError, match="no 2-character label"):
        seam_label(25**2 + 1, 2)
    with pytest.raises(ValueError, match="not a seam label"):
        label_number("9A")


def test_the_smallest_face_size_follows_the_label_length() -> None:
    plain = DrawingOptions(tabs=False)
    sizes = [smallest_face_size(plain, chars) for chars in (1, 2, 3, 4)]
    assert sizes == sorted(sizes) and sizes[2] < 9.0 < sizes[3]
    for chars, size in zip((1, 2, 3, 4), sizes):
        assert number_height(plain, size, chars) >= 2.0 > number_height(plain, round(size - 0.1, 1), chars)
    # With 3 mm tabs at 45 degrees no face under 7.5 mm will do, whatever the labels.
    assert smallest_face_size(DrawingOptions(), 2) == 7.5 and smallest_face_size(DrawingOptions(), 3) == sizes[2]
