"""Print-then-cut cutters: the registration marks their optical sensor reads and the area they cut in.

A home cutter finds a printed sheet by its marks, then cuts the lines of a
separate cut file in the marks' frame.  The print and the cut file therefore
carry the same marks at the same coordinates (:func:`registration_marks`),
and nothing printed or cut may come near them (:func:`cutter_area`).

- Silhouette (Silhouette Studio's "type 1" marks): a 5 mm solid square at the
  top-left corner and L-shaped marks at the top-right and bottom-left, 20 mm
  arms 0.5 mm thick, 10 mm in from the edges (Studio's default length,
  thickness and inset; 10 mm is the least inset Studio accepts).
- Cricut (Print Then Cut): Design Space cuts inside an area smaller than the
  page, at most 6.75 x 9.25 in (171.45 x 234.95 mm) on Letter and A4 for every
  machine (newer machines take more).  The marks here are L-shaped corners of that area,
  1.5 mm thick with one-inch arms, the weight of the corner marks Design Space prints.
"""

from __future__ import annotations

import dataclasses
from enum import Enum

import numpy as np

from ._polylines import Polylines

__all__ = ["CUTTERS", "Cutter", "CutterMarks", "clear_of_marks", "cutter_area", "registration_marks"]


class Cutter(Enum):
    """The cutter a coloured net is printed for."""

    NONE = "none"
    CRICUT = "cricut"
    SILHOUETTE = "silhouette"


@dataclasses.dataclass(frozen=True)
class CutterMarks:
    """A cutter's registration marks and the room they need, mm.

    Attributes
    ----------
    margin : float
        Least border of the sheet kept free of art and cuts (the marks sit in it).
    area : (float, float) or None
        Largest print-then-cut area, portrait (width, height), centred on the sheet; None: the whole
        sheet inside the margin.
    inset : float
        Distance of the marks from the sheet's edges (Silhouette) or gap from the area (Cricut).
    length, thickness : float
        Arm length and line weight of the L-shaped marks.
    square : float
        Side of the solid square mark (0: none).
    """

    margin: float
    area: tuple[float, float] | None
    inset: float
    length: float
    thickness: float
    square: float = 0.0


#: The marks of each cutter.  Silhouette: 10 mm inset + 5 mm square + 3 mm clear of the square.
CUTTERS: dict[Cutter, CutterMarks] = {
    Cutter.SILHOUETTE: CutterMarks(margin=18.0, area=None, inset=10.0, length=20.0, thickness=0.5, square=5.0),
    Cutter.CRICUT: CutterMarks(margin=0.0, area=(171.45, 234.95), inset=2.0, length=25.4, thickness=1.5),
}


def _box(cutter: Cutter, size: tuple[float, float], margin: float) -> tuple[float, float, float, float] | None:
    """The rectangle a Cricut cuts in: its area centred on the sheet, inside the room its marks take."""
    spec = CUTTERS.get(cutter)
    if spec is None or spec.area is None:
        return None
    w, h = size
    aw, ah = spec.area if w <= h else spec.area[::-1]
    edge = max(margin, spec.inset + spec.thickness)
    aw, ah = min(aw, w - 2 * edge), min(ah, h - 2 * edge)
    return ((w - aw) / 2, (h - ah) / 2, (w + aw) / 2, (h + ah) / 2)


def cutter_area(cutter: Cutter | str, size: tuple[float, float], margin: float
                ) -> tuple[float, float, float, float]:
    """``(x0, y0, x1, y1)`` of the sheet where art and cuts may go: inside the margin (at least the
    cutter's) and, for a Cricut, inside its print-then-cut area, mm."""
    cutter = Cutter(cutter)
    w, h = size
    spec = CUTTERS.get(cutter)
    m = max(margin, spec.margin) if spec else margin
    box = _box(cutter, size, margin)
    if box is None:
        return (m, m, w - m, h - m)
    return (max(m, box[0]), max(m, box[1]), min(w - m, box[2]), min(h - m, box[3]))


def _l_mark(x: float, y: float, sx: float, sy: float, length: float, t: float) -> np.ndarray:
    """An L with its outer corner at ``(x, y)``, arms along ``+-x`` and ``+-y`` (signs ``sx``, ``sy``)."""
    return np.array([(x, y), (x + sx * length, y), (x + sx * length, y + sy * t), (x + sx * t, y + sy * t),
                     (x + sx * t, y + sy * length), (x, y + sy * length)])


def registration_marks(cutter: Cutter | str, size: tuple[float, float], margin: float = 0.0) -> Polylines:
    """The cutter's marks on a sheet of ``size`` (mm, y up) as closed rings printed solid; empty for none."""
    cutter = Cutter(cutter)
    spec = CUTTERS.get(cutter)
    if spec is None:
        return Polylines.empty()
    w, h = size
    L, t, i = spec.length, spec.thickness, spec.inset
    if cutter is Cutter.SILHOUETTE:
        s = spec.square
        rings = [np.array([(i, h - i - s), (i + s, h - i - s), (i + s, h - i), (i, h - i)]),
                 _l_mark(w - i, h - i, -1, -1, L, t), _l_mark(i, i, 1, 1, L, t)]
    else:
        x0, y0, x1, y1 = _box(cutter, size, margin)  # type: ignore[misc]
        g = i + t  # the marks' outer corners, a gap outside the area
        rings = [_l_mark(x0 - g, y1 + g, 1, -1, L, t), _l_mark(x1 + g, y1 + g, -1, -1, L, t),
                 _l_mark(x0 - g, y0 - g, 1, 1, L, t), _l_mark(x1 + g, y0 - g, -1, 1, L, t)]
    return Polylines.from_list(rings, [True] * len(rings))


#: Least gap between a registration mark and anything else printed, mm: the sensor reads the marks
#: by the blank paper round them.
MARK_CLEARANCE = 3.0


def clear_of_marks(cutter: Cutter | str, size: tuple[float, float], margin: float, x0: float,
                   band: tuple[float, float]) -> float:
    """The least x at or after ``x0`` where a line of text in heights ``band`` (mm, y up) starts clear of
    the marks in the sheet's left half (a Silhouette's bottom-left L reaches 30 mm in, past the margin)."""
    marks = registration_marks(cutter, size, margin)
    for ring in marks.lines():
        lo, hi = ring.min(axis=0), ring.max(axis=0)
        if lo[0] < size[0] / 2 and lo[1] - MARK_CLEARANCE < band[1] and band[0] < hi[1] + MARK_CLEARANCE:
            x0 = max(x0, float(hi[0]) + MARK_CLEARANCE)
    return x0
