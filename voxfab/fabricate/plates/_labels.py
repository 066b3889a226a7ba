"""Single-stroke plate labels: a tiny stroke font and a placement search.

Labels are engraved as open polylines (one laser pass, no fonts needed by the
shop).  A label goes where the next plate of the stack covers it, so it is
hidden in the finished sculpture; when no such place is big enough it goes
anywhere on the plate, and at worst it is shrunk to the smallest size,
:data:`MIN_HEIGHT` (the nets' smallest label).  A label is engraved whole or
not at all: a clipped one could read as another plate's ("5-1." of "25-1.1"),
so a plate too small for its label is named on the assembly plan instead.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

from voxfab.drawing import text_polylines, text_width

#: Label heights tried, as fractions of the pitch, largest first.
_HEIGHTS = (0.6, 0.45, 0.32, 0.22)
#: Smallest label height in mm that is still engraved legibly: the nets' smallest seam label.
MIN_HEIGHT = 2.0


def full_height(pitch: float) -> float:
    """The height a label is engraved at when its plate has room: the largest tried."""
    return max(MIN_HEIGHT, _HEIGHTS[0] * pitch)


def text_size(text: str, height: float) -> tuple[float, float]:
    """Width and height in mm of ``text`` drawn ``height`` mm tall."""
    return text_width(text, height), height


def text_strokes(text: str, height: float) -> tuple[npt.NDArray[np.float64], ...]:
    """Polylines of ``text`` in mm, ``height`` tall, lower-left corner at the origin.

    The glyphs are voxfab's single-stroke font, shared with the net drawings.

    Parameters
    ----------
    text : str
        Digits, ``'-'`` and ``'.'`` (plate numbers).
    height : float
        Glyph height in mm.

    Returns
    -------
    strokes : tuple of (n, 2) float ndarray
        Open polylines.
    """
    lines = text_polylines([text], [(0.0, 0.0)], [(1.0, 0.0)], height)
    return tuple(
        lines.points[a:b].copy() for a, b in zip(lines.offsets[:-1], lines.offsets[1:])
    )


@dataclasses.dataclass(frozen=True, eq=False)
class Label:
    """An engraved label placed on a plate.

    Attributes
    ----------
    text : str
        The plate number (``"layer-piece"``, plus ``".copy"`` when a layer takes
        several plates).
    strokes : tuple of (n, 2) float ndarray
        Polylines in the plate's frame (mm).
    height : float
        Glyph height in mm.
    hidden : bool
        Whether the next plate of the stack covers the label.
    complete : bool
        False when the plate is too small even for the smallest label: nothing is
        engraved (no strokes), and the plate is named on the assembly plan.
    origin : (float, float)
        Lower-left corner of the text box on the plate (mm).
    turned : bool
        Whether the text reads upwards (turned 90° counter-clockwise).
    """

    text: str
    strokes: tuple[npt.NDArray[np.float64], ...]
    height: float
    hidden: bool
    complete: bool = True
    origin: tuple[float, float] = (0.0, 0.0)
    turned: bool = False


def _render(text: str, height: float, origin: tuple[float, float], turned: bool) -> tuple[npt.NDArray[np.float64], ...]:
    strokes = text_strokes(text, height)
    if turned:
        # turned 90° counter-clockwise: (x, y) → (h − y, x), reading upwards
        strokes = tuple(np.column_stack([height - s[:, 1], s[:, 0]]) for s in strokes)
    return tuple(s + origin for s in strokes)


def relabel(label: Label, text: str) -> Label | None:
    """The same placement with another text of the same length, or None if it cannot be reused."""
    if len(text) != len(label.text) or not label.complete:
        return None
    strokes = _render(text, label.height, label.origin, label.turned)
    return dataclasses.replace(label, text=text, strokes=strokes)


def _fit(
    region: object, core: object, width: float, height: float, step: float, pole: tuple[float, float]
) -> tuple[float, float] | None:
    """Lower-left corner of a ``width × height`` box inside ``region`` nearest ``pole``.

    Box centres are tried on a ``step`` lattice, only inside ``core``: the
    region shrunk by half the box's short side (a necessary condition).
    """
    import shapely

    x0, y0, x1, y1 = region.bounds
    if x1 - x0 < width or y1 - y0 < height:
        return None
    cx0, cy0, cx1, cy1 = core.bounds
    step = max(step, max(cx1 - cx0, cy1 - cy0) / 48.0)  # at most ~48² candidates
    # lattice through the pole, so the pole itself is always tried
    xs = pole[0] + step * np.arange(np.ceil((cx0 - pole[0]) / step - 1e-9), np.floor((cx1 - pole[0]) / step + 1e-9) + 1)
    ys = pole[1] + step * np.arange(np.ceil((cy0 - pole[1]) / step - 1e-9), np.floor((cy1 - pole[1]) / step + 1e-9) + 1)
    gx, gy = (a.ravel() for a in np.meshgrid(xs, ys, indexing="ij"))
    shapely.prepare(core)
    keep = shapely.contains_xy(core, gx, gy)
    gx, gy = gx[keep] - width / 2.0, gy[keep] - height / 2.0
    if len(gx) == 0:
        return None
    order = np.argsort(np.hypot(gx + width / 2 - pole[0], gy + height / 2 - pole[1]), kind="stable")
    gx, gy = gx[order], gy[order]
    shapely.prepare(region)
    # nearest candidates first, in small batches: the first fit is usually close
    for lo in range(0, len(gx), 64):
        bx, by = gx[lo:lo + 64], gy[lo:lo + 64]
        ok = shapely.contains(region, shapely.box(bx, by, bx + width, by + height))
        if ok.any():
            i = int(np.argmax(ok))
            return float(bx[i]), float(by[i])
    return None


def place_label(text: str, plate: object, hidden_region: object, *, pitch: float, clearance: float,
                sizes: tuple[float, ...] | None = None, upright: bool = False, fallback: bool = True) -> Label | None:
    """Place ``text`` on ``plate``, inside ``hidden_region`` when it fits.

    Parameters
    ----------
    text : str
        The label text.
    plate : shapely.Polygon
        The plate in mm, dowel holes already cut out.
    hidden_region : shapely geometry
        Part of the plate that the next plate covers (mm).
    pitch : float
        Voxel pitch in mm; label sizes scale with it.
    clearance : float
        Distance in mm kept between the label and any edge of its region.
    sizes : tuple of float, optional
        Heights in mm to try, largest first (default: fractions of the pitch); none under :data:`MIN_HEIGHT`.
    upright : bool
        Only horizontal text, never turned.
    fallback : bool
        When nothing fits: a label with no strokes, ``complete`` False (True), or None.

    Returns
    -------
    Label or None
        Horizontal when it fits, else turned 90° counter-clockwise.
    """
    from shapely.ops import polylabel

    asked = sizes if sizes is not None else [f * pitch for f in _HEIGHTS]
    heights = sorted({max(MIN_HEIGHT, h) for h in asked}, reverse=True)
    tight = min(clearance, 0.1)
    passes = ((hidden_region, True, clearance), (hidden_region, True, tight), (plate, False, clearance), (plate, False, tight))
    for region, hidden, clear in passes:
        inner = region.buffer(-clear, join_style="mitre")
        if inner.is_empty:
            continue
        parts = getattr(inner, "geoms", [inner])
        biggest = max(parts, key=lambda p: p.area)
        c = polylabel(biggest, tolerance=0.05 * pitch)
        pole = (c.x, c.y)
        for h in heights:
            w, _ = text_size(text, h)
            core = inner.buffer(-min(w, h) / 2.0, join_style="mitre")
            if core.is_empty:
                continue
            # a coarse lattice first; a fine one only where the coarse one found no room
            for step in (max(0.1, 0.125 * pitch), max(0.025, 0.03 * pitch)):
                for turned, (bw, bh) in ((False, (w, h)),) + (() if upright else ((True, (h, w)),)):
                    at = _fit(inner, core, bw, bh, step, pole)
                    if at is not None:
                        return Label(text, _render(text, h, at, turned), h, hidden, origin=at, turned=turned)
    if not fallback:
        return None
    # Nothing fits whole: nothing is engraved (a clipped label could read as another plate's).
    return Label(text, (), heights[-1], False, complete=False)
