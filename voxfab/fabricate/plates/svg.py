"""Sheet → SVG in mm (``width``/``height`` in mm and a matching ``viewBox``).

Colours follow the common laser convention: cut red, score blue, engrave
black, all hairline strokes without fill.  SVG's y axis points down, so sheet
coordinates are flipped.
"""

from __future__ import annotations

from xml.sax.saxutils import quoteattr

import numpy as np
import numpy.typing as npt

from voxfab._shared.atomic import write_text
from voxfab._shared.typing import PathLike

from ._nest import Sheet

__all__ = ["COLOURS", "STROKE_WIDTH", "sheet_svg", "write_svg"]

#: Layer → stroke colour.
COLOURS: dict[str, str] = {"CUT": "#FF0000", "SCORE": "#0000FF", "ENGRAVE": "#000000"}
#: Hairline stroke width in mm.
STROKE_WIDTH = 0.01


def _num(v: float) -> str:
    s = f"{v:.4f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _path(xy: npt.NDArray[np.float64], height: float, *, closed: bool) -> str:
    pts = [f"{_num(x)} {_num(height - y)}" for x, y in xy]
    return "M" + " L".join(pts) + (" Z" if closed else "")


def sheet_svg(sheet: Sheet) -> str:
    """Return the SVG text of one sheet (one group per layer, one path per part)."""
    h = sheet.height
    groups: dict[str, list[str]] = {name: [] for name in COLOURS}
    for part in sheet.parts:
        pid = quoteattr(part.plate.label.text)
        rings = " ".join(_path(r[:-1], h, closed=True) for r in part.cut)
        groups["CUT"].append(f'<path data-plate={pid} fill-rule="evenodd" d="{rings}"/>')
        for x, y, r in part.circles:
            groups["CUT"].append(f'<circle data-plate={pid} cx="{_num(x)}" cy="{_num(h - y)}" r="{_num(r)}"/>')
        if part.score:
            d = " ".join(_path(a, h, closed=False) for a in part.score)
            groups["SCORE"].append(f'<path data-plate={pid} d="{d}"/>')
        if part.engrave:
            d = " ".join(_path(a, h, closed=False) for a in part.engrave)
            groups["ENGRAVE"].append(f'<path data-plate={pid} d="{d}"/>')
    w = _num(sheet.width)
    hh = _num(h)
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{w}mm" height="{hh}mm" viewBox="0 0 {w} {hh}">',
        f"<title>sheet {sheet.index}</title>",
    ]
    for name, items in groups.items():
        lines.append(
            f'<g id="{name}" fill="none" stroke="{COLOURS[name]}" stroke-width="{STROKE_WIDTH}" '
            'stroke-linecap="round" stroke-linejoin="round">'
        )
        lines.extend(items)
        lines.append("</g>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


def write_svg(sheet: Sheet, path: PathLike) -> None:
    """Write one sheet as SVG to ``path`` (atomically)."""
    write_text(path, sheet_svg(sheet))
