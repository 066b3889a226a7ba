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

__all__ = ["construction_drawing", "construction_pdf", "write_construction_pdf"]

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
    for p, bar in zip(construction.plates, bars):
        ring = np.asarray(bar.exterior.coords)[:-1] * k + shift
        rings.setdefault(p.family, []).append(ring)
        # the label sits beyond the bar's far end, so every bar can be named
        far = ring[np.argmax(ring @ np.array([1.0, 0.37]))]
        _text(label, p.label.text, float(far[0]) + 1.0, float(far[1]) + 1.0, 2.2)
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
