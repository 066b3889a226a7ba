"""SVG writer: mm units with a matching viewBox, hairline strokes, one group per layer.

Each layer is an Inkscape layer (a ``<g>`` with ``inkscape:groupmode="layer"``)
whose stroke colour comes from the colour map, so LightBurn, Glowforge and
Inkscape all see the same layer split.  y grows downwards in SVG, so the drawing
is flipped on output.
"""

from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import escape

import numpy as np

from voxfab._shared.atomic import write_text

from ._drawing import Drawing, Sheet
from ._format import numbers, polyline_text
from ._options import DASH_PATTERNS, LAYERS, LayerStyle

#: Stroke width of every line, mm: thin enough to count as a vector "hairline".
HAIRLINE = 0.01


def sheet_svg(sheet: Sheet, styles: dict[str, LayerStyle], *, title: str = "") -> str:
    """The SVG document of one sheet."""
    w, h = numbers([sheet.width, sheet.height])
    out = [
        '<?xml version="1.0" encoding="UTF-8" standalone="no"?>\n',
        '<svg xmlns="http://www.w3.org/2000/svg" '
        'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" version="1.1" '
        f'width="{w}mm" height="{h}mm" viewBox="0 0 {w} {h}">\n',
    ]
    if title:
        out.append(f"<title>{escape(title)}</title>\n")
    for name in LAYERS:
        lines = sheet.layers[name]
        if not len(lines):
            continue
        st = styles[name]
        dash = DASH_PATTERNS[st.style]
        dash_attr = f' stroke-dasharray="{" ".join(numbers(dash))}"' if dash else ""
        out.append(
            f'<g id="{name}" inkscape:groupmode="layer" inkscape:label="{name}" fill="none" '
            f'stroke="{st.color}" stroke-width="{HAIRLINE}"{dash_attr} stroke-linecap="butt" '
            'stroke-linejoin="miter">\n'
        )
        pts = lines.points.copy()
        pts[:, 1] = sheet.height - pts[:, 1]
        ends = np.where(lines.closed, ' Z"/>\n', '"/>\n')
        out.append(polyline_text(pts, lines.offsets, '<path d="M%s,%s', " L%s,%s", ends))
        out.append("</g>\n")
    out.append("</svg>\n")
    return "".join(out)


def write_svg(drawing: Drawing, paths: list[Path], styles: dict[str, LayerStyle], *, title: str = "") -> list[str]:
    """Write one SVG per sheet to ``paths``; returns the paths written."""
    for sheet, path in zip(drawing.sheets, paths):
        write_text(path, sheet_svg(sheet, styles, title=title))
    return [str(p) for p in paths]
