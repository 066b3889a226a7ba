"""Assembly instructions as PDF: the stack order as a grid of layers, drawn with the drawing backends.

Each panel shows one voxel layer from above: its pieces shaded and numbered,
the layer below as a dotted outline (where to glue it) and the dowel holes.
Panels run left to right, top to bottom, from the bottom layer up, 25 to an A4
page.  Text is the single-stroke font, so the PDF needs no fonts, and it
carries no dates, so equal stacks give equal bytes.
"""

from __future__ import annotations

import math

import numpy as np

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike
from voxfab.drawing import Drawing, Fill, Page, Polylines, text_polylines, text_width

from ._outline import cells_outline, scaled
from ._stack import PlateStack

__all__ = ["PANELS_PER_PAGE", "assembly_drawing", "assembly_pdf", "write_assembly_pdf"]

#: Layers drawn per page (a 5 × 5 grid fits the artist's 25 layers on one page).
PANELS_PER_PAGE = 25
#: Page size (A4 portrait) and margin, mm.
PAGE = (210.0, 297.0)
MARGIN = 10.0
#: Shade of the pieces.
PIECE_FILL = "#f2c48d"
#: Cap heights of the heading and the panel captions, mm.
HEADING = 3.0
CAPTION = 2.2


def _rings(geometry: object) -> list[np.ndarray]:
    out = []
    for poly in getattr(geometry, "geoms", [geometry]):
        if poly.is_empty:
            continue
        out.append(np.asarray(poly.exterior.coords)[:-1])
        out.extend(np.asarray(r.coords)[:-1] for r in poly.interiors)
    return out


def _text(lines: list[Polylines], text: str, x: float, y: float, height: float, *, center: bool = False,
          width: float | None = None) -> None:
    """Add ``text`` at baseline ``(x, y)``, shrunk to ``width`` when given."""
    if width is not None:
        height = min(height, width / max(text_width(text, 1.0), 1e-9))
    lines.append(text_polylines([text], [(x, y)], [(1.0, 0.0)], height, center=center))


def _per_layer(stack: PlateStack) -> str:
    """``"2 PLATE(S)"``, or ``"1-2 PLATE(S)"`` when the layers were resampled unevenly."""
    lo, hi = min(stack.counts), max(stack.counts)
    return f"{lo} PLATE(S)" if lo == hi else f"{lo}-{hi} PLATE(S)"


#: Plate names per heading line of the plates left unengraved.
NAMES_PER_LINE = 10


def _heading(stack: PlateStack, title: str) -> list[str]:
    n = len(stack.layers)
    lines = [
        f"{title + ': ' if title else ''}STACK ORDER LAYER 1 (BOTTOM) TO {n} (TOP) - AXIS {stack.axis} - "
        f"{_per_layer(stack)} OF {stack.thickness:g} MM PER LAYER",
        "SHADED: THIS LAYER WITH ITS PIECE NUMBERS - DOTTED: THE LAYER BELOW - CIRCLES: DOWEL HOLES",
    ]
    # A plate too small for a whole label carries none: the plan names it, by its layer and piece.
    bare = [p.label.text for p in stack.plates if not p.label.complete]
    for k in range(0, len(bare), NAMES_PER_LINE):
        head = "NOT ENGRAVED (TOO SMALL FOR A LABEL): " if k == 0 else ""
        lines.append(head + " ".join(bare[k:k + NAMES_PER_LINE]))
    return lines


def _page(stack: PlateStack, start: int, unions: list, lo: np.ndarray, size: np.ndarray, title: str) -> Page:
    from shapely.ops import polylabel

    count = min(PANELS_PER_PAGE, len(stack.layers) - start)
    cols = math.ceil(math.sqrt(count))
    rows = math.ceil(count / cols)
    gap = 0.15 * float(np.max(size))
    cell = size + gap
    heading = _heading(stack, title.upper())
    top = PAGE[1] - MARGIN - HEADING * (2 * len(heading) + 1)
    k = min((PAGE[0] - 2 * MARGIN) / (cols * cell[0]), (top - MARGIN) / (rows * cell[1]))
    pitch = stack.pitch
    cut: list[np.ndarray] = []
    below: list[np.ndarray] = []
    label: list[Polylines] = []
    holes: list[tuple[float, float, float]] = []
    for i, line in enumerate(heading):
        _text(label, line, MARGIN, PAGE[1] - MARGIN - HEADING - i * 2 * HEADING, HEADING, width=PAGE[0] - 2 * MARGIN)
    for i in range(count):
        layer = start + i
        r, c = divmod(i, cols)
        # Panel origin on the page: its drawing's lower-left corner.
        ox = MARGIN + (c * cell[0] + gap / 2) * k
        oy = top - ((r + 1) * cell[1]) * k
        shift = np.array([ox, oy]) - lo * k
        if layer > 0 and unions[layer - 1] is not None:
            below.extend(ring * k + shift for ring in _rings(scaled(unions[layer - 1], pitch)))
        for piece in stack.layers[layer]:
            poly = scaled(piece.outline, pitch)
            cut.extend(ring * k + shift for ring in _rings(poly))
            at = np.array(polylabel(poly, tolerance=0.05 * pitch).coords)[0] * k + shift
            _text(label, piece.id, float(at[0]), float(at[1]) - 0.75, 1.5, center=True)
        for d in stack.dowels:
            if int(d.lower.split("-")[0]) == layer + 1 or int(d.upper.split("-")[0]) == layer + 1:
                x, y = np.array([d.x, d.y]) * k + shift
                holes.append((float(x), float(y), stack.dowel_diameter / 2 * k))
        first, last = stack.plate_range(layer)
        plates = f"PLATE {first}" if first == last else f"PLATES {first}-{last}"
        _text(label, f"LAYER {layer + 1} ({plates})", ox + size[0] * k / 2, oy + (size[1] + 0.3 * gap) * k,
              CAPTION, center=True, width=0.9 * cell[0] * k)
    rings = Polylines.from_list(cut, [True] * len(cut))
    return Page(
        PAGE[0], PAGE[1],
        layers={"CUT": rings, "GRID": Polylines.from_list(below, [True] * len(below)),
                "LABEL": Polylines.concat(label)},
        circles={"CUT": np.array(holes, dtype=np.float64).reshape(-1, 3)},
        fills=(Fill(rings, PIECE_FILL),),
    )


def assembly_drawing(stack: PlateStack, *, title: str = "") -> Drawing:
    """The assembly instructions of ``stack`` as a drawing (one A4 page per 25 layers)."""
    unions = [cells_outline(np.concatenate([p.cells for p in pcs])) if pcs else None for pcs in stack.layers]
    bounds = np.array([u.bounds for u in unions if u is not None]).reshape(-1, 4)
    lo = bounds[:, :2].min(axis=0) * stack.pitch
    size = bounds[:, 2:].max(axis=0) * stack.pitch - lo
    pages = tuple(_page(stack, start, unions, lo, size, title)
                  for start in range(0, len(stack.layers), PANELS_PER_PAGE))
    return Drawing(pages, title or "plate stack")


def assembly_pdf(stack: PlateStack, *, title: str = "") -> bytes:
    """Return the assembly PDF of ``stack`` as bytes (one page per 25 layers)."""
    from voxfab.drawing.pdf import pdf_document

    return pdf_document(assembly_drawing(stack, title=title), creator="voxfab slices")


def write_assembly_pdf(stack: PlateStack, path: PathLike, *, title: str = "") -> None:
    """Write the assembly PDF of ``stack`` to ``path`` (atomically)."""
    write_bytes(path, assembly_pdf(stack, title=title))
