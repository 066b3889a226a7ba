"""Legible marks: how tall edge labels and how deep glue tabs a face size allows, and the smallest that works.

An edge label (:mod:`._labels`) sits inside its face along the edge, centred
or, when long, pushed towards the edge's end so that labels on neighbouring
edges of one face never meet at a corner; the height a face allows depends on
the characters of a label, the same for every seam of a net.  A glue tab is a trapezoid with sides at the
tab angle on an edge inset from both corners (:func:`._tabs.tab_heights`).
"""

from __future__ import annotations

import math

from voxfab.drawing._font import CAP_HEIGHT, GLYPH_WIDTH

from ._options import DrawingOptions
from ._tabs import tab_heights

#: Gap between the face edge and the baseline of its label, as a fraction of the face size.
NUMBER_INSET = 0.04
#: Clear gap between a label's end and the next corner, as a fraction of the face size.  With the inset,
#: 0.06 of the face: what the letter-wide gap between labels (:data:`LABEL_GAP`) takes from them, so
#: labels of up to three characters are as tall on a face as with half that gap.
NUMBER_GAP = 0.02
#: Font units from one character of a label to the next: with glyphs 4 wide, a letter gap of a
#: sixth of the cap height (ordinary letter spacing), so a label reads as one word.
LABEL_ADVANCE = 5.0
#: Clear gap between the labels of neighbouring edges at a corner, as a fraction of the label height:
#: a letter's width, four letter gaps, so two labels meeting at a corner never read as one ("0R" "1A",
#: not "0R1A").
LABEL_GAP = GLYPH_WIDTH / CAP_HEIGHT
#: Largest label height as a fraction of the face size (larger ones look shouty).
NUMBER_MAX = 0.3


def number_start(pitch: float, height: float) -> float:
    """Least distance along its edge at which a label starts, mm.

    Each label reads along its edge with the face on its left, so the label
    of the previous edge (counter-clockwise) lies in a strip ``inset + height``
    deep along the start of this edge; starting :data:`LABEL_GAP` label heights
    past that strip, labels on neighbouring edges never meet, however long they
    are.
    """
    return NUMBER_INSET * pitch + (1.0 + LABEL_GAP) * height


def number_ratio(chars: int) -> float:
    """Largest label height per mm of face size for labels of ``chars`` characters.

    A label starts at :func:`number_start` and must end a gap before the next
    corner: ``inset p + (1 + label gap) h + w h <= (1 - gap) p`` with ``w`` the
    text width per mm of height.
    """
    width = ((chars - 1) * LABEL_ADVANCE + GLYPH_WIDTH) / CAP_HEIGHT  # per mm of height
    return min((1.0 - NUMBER_INSET - NUMBER_GAP) / (1.0 + LABEL_GAP + width), NUMBER_MAX)


def number_height(options: DrawingOptions, pitch: float, chars: int) -> float:
    """Cap height of the edge labels at face size ``pitch``, mm."""
    return min(float(options.label_height), number_ratio(chars) * pitch)


def tab_depth(options: DrawingOptions, pitch: float) -> float:
    """Height of a full glue tab at face size ``pitch``, mm (0 without tabs)."""
    if not options.tabs:
        return 0.0
    return tab_heights(pitch, options.tab_width, options.tab_angle)[1]


def _round_up(x: float) -> float:
    return math.ceil(x * 10.0 - 1e-6) / 10.0


def smallest_face_size(options: DrawingOptions, chars: int) -> float:
    """Smallest face size (0.1 mm steps) whose labels and tabs reach the minimums, mm."""
    need = 0.0
    if options.numbers:
        need = options.min_label_height / number_ratio(chars)
    if options.tabs:
        # tab height = 0.45 (p - 2 inset) tan(angle), inset = min(0.5, 0.05 p)
        base = options.min_tab_depth / (0.45 * math.tan(math.radians(options.tab_angle)))
        need = max(need, base + 1.0 if base + 1.0 >= 10.0 else base / 0.9)
    p = _round_up(need)
    while (options.numbers and number_height(options, p, chars) < options.min_label_height - 1e-9) or (
        options.tabs and tab_depth(options, p) < options.min_tab_depth - 1e-9
    ):
        p = round(p + 0.1, 1)
    return p


def legibility_problem(options: DrawingOptions, pitch: float, chars: int) -> str | None:
    """Why faces of ``pitch`` mm are too small for the marks, or None when they are big enough."""
    short, outs = [], []
    if options.numbers:
        h = number_height(options, pitch, chars)
        if h < options.min_label_height - 1e-9:
            short.append(f"{options.min_label_height:g} mm edge labels of {chars} character{'s' if chars > 1 else ''} "
                         f"(they would be {h:.1f} mm)")
            outs.append("--no-numbers")
    if options.tabs:
        t = tab_depth(options, pitch)
        if t < options.min_tab_depth - 1e-9:
            short.append(f"{options.min_tab_depth:g} mm glue tabs (they would be {t:.1f} mm)")
            outs.append("--no-tabs")
    if not short:
        return None
    return (
        f"faces of {pitch:g} mm are too small for {' and '.join(short)}; the smallest face size that "
        f"works is {smallest_face_size(options, chars):g} mm, or draw without them ({', '.join(outs)})"
    )
