"""Assembly instructions of a slotted construction as PDF: the order of slotting, and a plan view.

The plan looks along the crossing axis (z for radial plates and for the
default interlocked axes): every plate shows as a shaded bar with its label,
family A bars in one shade and family B in another, and the numbered steps
say which plates stand first and which slide onto them.  Text is the
single-stroke font and there are no dates, so equal constructions give equal bytes.
"""

from __future__ import annotations

import numpy as np

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike
from voxfab.drawing import Drawing, Fill, Page, Polylines, text_polylines, text_width

from ._slotted import Construction

__all__ = ["construction_drawing", "construction_pdf", "plan_label_boxes", "write_construction_pdf"]

PAGE = (210.0, 297.0)
MARGIN = 10.0
HEADING = 3.0
STEP = 2.6
SHADES = {"A": "#f2c48d", "B": "#9fc5e8", "R": "#f2c48d"}


def _text(lines: list[Polylines], text: str, x: float, y: float, height: float, *, center: bool = False,
          width: float | None = None) -> None:
    if width is not None:
        height = min(height, width / max(text_width(text, 1.0), 1e-9))
    lines.append(text_polylines([text], [(x, y)], [(1.0, 0.0)], height, center=center))


def _wrap(text: str, height: float, width: float) -> list[str]:
    """Split ``text`` at spaces into lines no wider than ``width`` mm at ``height``."""
    out: list[str] = []
    line = ""
    for word in text.split():
        trial = f"{line} {word}".strip()
        if line and text_width(trial, height) > width:
            out.append(line)
            line = word
        else:
            line = trial
    return out + ([line] if line else [])


def _view_axis(construction: Construction) -> int:
    """The axis the plan looks along: the one every plate contains (the crossing axis)."""
    if construction.style == "radial":
        return 2
    normals = np.array([np.abs(p.normal) for p in construction.plates])
    return int(np.argmin(normals.max(axis=0)))


#: Height of the plate labels in the plan, mm.
PLAN_LABEL = 2.2


def plan_label_boxes(rings: list[np.ndarray], texts: list[str], *, height: float = PLAN_LABEL,
                     page: tuple[float, float] = PAGE) -> list[tuple[float, float, float, float]]:
    """Where each bar's label goes in the plan: ``(x0, y0, x1, y1)`` of its text, no two overlapping.

    Tried in order: beyond the bar's far end (up and to the right), beyond its near
    end, then above, below, left and right of the bar; the first spot clear of every
    bar and of the labels already placed wins, on the page.  Only when none is clear
    does the label take the spot nearest its bar that overlaps no other label.
    """
    import shapely

    bars = [shapely.Polygon(r) for r in rings]
    placed: list[object] = []
    out = []
    direction = np.array([1.0, 0.37])
    for ring, text, bar in zip(rings, texts, bars):
        w = text_width(text, height)
        far, near = ring[np.argmax(ring @ direction)], ring[np.argmin(ring @ direction)]
        x0, y0, x1, y1 = bar.bounds
        cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
        spots = [(far[0] + 1.0, far[1] + 1.0), (near[0] - 1.0 - w, near[1] - 1.0 - height),
                 (cx - w / 2, y1 + 1.0), (cx - w / 2, y0 - 1.0 - height),
                 (x0 - 1.0 - w, cy - height / 2), (x1 + 1.0, cy - height / 2)]
        # then a ring of spots around the bar, further out each round
        spots += [(cx + r * np.cos(a) - w / 2, cy + r * np.sin(a) - height / 2)
                  for r in np.arange(1.0, 6.0) * (max(x1 - x0, y1 - y0) / 2 + height)
                  for a in np.linspace(0, 2 * np.pi, 16, endpoint=False)]
        boxes = [shapely.box(x, y, x + w, y + height) for x, y in spots]
        on_page = [b for b in boxes if b.bounds[0] >= 0 and b.bounds[1] >= 0 and b.bounds[2] <= page[0]
                   and b.bounds[3] <= page[1]] or boxes
        clear = [b for b in on_page if not any(b.intersects(o) for o in placed)]
        best = next((b for b in clear if not any(b.intersects(o) for o in bars)), clear[0] if clear else on_page[0])
        placed.append(best.buffer(0.3, join_style="mitre"))
        out.append(tuple(float(v) for v in best.bounds))
    return out


def construction_drawing(construction: Construction, *, title: str = "") -> Drawing:
    """One A4 page: heading, plan view of the plates with their labels, and the numbered steps."""
    import shapely

    from ._assembly import plate_solid_mesh

    look = _view_axis(construction)
    keep = [k for k in range(3) if k != look]
    bars = []
    for p in construction.plates:
        v, _ = plate_solid_mesh(p)
        bars.append(shapely.MultiPoint(v[:, keep]).convex_hull)
    lo = np.min([b.bounds[:2] for b in bars], axis=0)
    hi = np.max([b.bounds[2:] for b in bars], axis=0)
    size = np.maximum(hi - lo, 1e-6)
    label: list[Polylines] = []
    heading = (f"{title.upper() + ': ' if title else ''}{construction.style.upper()} PLATES - "
               f"{len(construction.plates)} PLATES OF {construction.thickness:g} MM - "
               f"PLAN LOOKING DOWN {'XYZ'[look]}")
    _text(label, heading, MARGIN, PAGE[1] - MARGIN - HEADING, HEADING, width=PAGE[0] - 2 * MARGIN)
    steps = [f"{i}. {s.upper()}" for i, s in enumerate(construction.steps, start=1)]
    steps.append(f"{len(steps) + 1}. EACH SLOT IS ENGRAVED WITH THE LABEL OF THE PLATE THAT GOES INTO IT")
    lines = [ln for s in steps for ln in _wrap(s, STEP, PAGE[0] - 2 * MARGIN)]
    y = PAGE[1] - MARGIN - 3 * HEADING
    for ln in lines:
        _text(label, ln, MARGIN, y, STEP)
        y -= 1.8 * STEP
    top = y - STEP
    room = np.array([PAGE[0] - 2 * MARGIN, top - MARGIN - 6.0])
    k = float(np.min(room / size))
    shift = np.array([MARGIN, MARGIN + 6.0]) + (room - size * k) / 2 - lo * k
    rings: dict[str, list[np.ndarray]] = {}
    placed = [np.asarray(bar.exterior.coords)[:-1] * k + shift for bar in bars]
    texts = [p.label.text for p in construction.plates]
    for p, ring, box in zip(construction.plates, placed, plan_label_boxes(placed, texts)):
        rings.setdefault(p.family, []).append(ring)
        # every bar named, its label clear of the other bars and labels where the page has room
        _text(label, p.label.text, box[0], box[1], PLAN_LABEL)
    cut = [r for fam in sorted(rings) for r in rings[fam]]
    fills = tuple(Fill(Polylines.from_list(rings[f], [True] * len(rings[f])), SHADES.get(f, "#dddddd"))
                  for f in sorted(rings))
    page = Page(PAGE[0], PAGE[1], layers={"CUT": Polylines.from_list(cut, [True] * len(cut)),
                                          "LABEL": Polylines.concat(label)}, fills=fills)
    return Drawing((page,), title or f"{construction.style} plates")


def construction_pdf(construction: Construction, *, title: str = "") -> bytes:
    """The assembly PDF of a slotted construction as bytes."""
    from voxfab.drawing.pdf import pdf_document

    return pdf_document(construction_drawing(construction, title=title), creator="voxfab slices")


def write_construction_pdf(construction: Construction, path: PathLike, *, title: str = "") -> None:
    """Write :func:`construction_pdf` to ``path`` (atomically)."""
    write_bytes(path, construction_pdf(construction, title=title))
