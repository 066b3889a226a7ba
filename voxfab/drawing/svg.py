"""SVG backend: mm units with a matching viewBox, one Inkscape layer per drawing layer.

Each layer is a ``<g>`` with ``inkscape:groupmode="layer"`` whose stroke colour
and dashes come from the layer table, so LightBurn, Glowforge and Inkscape all
see the same layer split.  Laser files get hairline strokes; previews get the
layers' visible widths and the drawing's fills, so a browser shows the lines.
SVG's y axis points down, so pages are flipped on output.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from html import escape
from pathlib import Path

import numpy as np

from voxfab._shared.atomic import write_text

from ._format import numbers, polyline_text
from ._layers import DASH_PATTERNS, LAYERS, LayerStyle, Lines
from ._model import HALO, Page
from ._polylines import Polylines

__all__ = ["page_svg", "write_svg"]


def _paths(lines: Polylines, height: float) -> str:
    pts = lines.points.copy()
    pts[:, 1] = height - pts[:, 1]
    ends = np.where(lines.closed, ' Z"/>\n', '"/>\n')
    return polyline_text(pts, lines.offsets, '<path d="M%s,%s', " L%s,%s", ends)


def _fills(page: Page) -> list[str]:
    out = ['<g id="FILL" inkscape:groupmode="layer" inkscape:label="FILL" stroke="none" fill-rule="evenodd">\n']
    for fill in page.fills:
        rings = fill.rings
        if not len(rings):
            continue
        pts = rings.points.copy()
        pts[:, 1] = page.height - pts[:, 1]
        if fill.colors:  # a path per ring, each in its colour
            first = [f'<path id="{escape(n)}" fill="{c}" d="M%s,%s' if n else f'<path fill="{c}" d="M%s,%s'
                     for c, n in zip(fill.colors, fill.names or ("",) * len(fill.colors))]
            out.append(polyline_text(pts, rings.offsets, first, " L%s,%s", ' Z"/>\n'))
            continue
        d = polyline_text(pts, rings.offsets, "M%s,%s", " L%s,%s", " Z ")
        name = f' id="{escape(fill.name)}"' if fill.name else ""
        rule = ' fill-rule="nonzero"' if fill.nonzero else ""
        out.append(f'<path{name} fill="{fill.color}"{rule} d="{d.rstrip()}"/>\n')
    out.append("</g>\n")
    return out


def _images(page: Page) -> list[str]:
    """The placed pictures as embedded PNGs, y flipped like the lines."""
    import base64

    from PIL import Image

    from .png import png_bytes

    out = []
    for placed in page.images:
        data = base64.b64encode(png_bytes(Image.fromarray(placed.pixels, "RGB"))).decode("ascii")
        x, y, w, h = numbers([placed.x, page.height - placed.y - placed.height, placed.width, placed.height])
        out.append(f'<image x="{x}" y="{y}" width="{w}" height="{h}" preserveAspectRatio="none" '
                   f'href="data:image/png;base64,{data}"/>\n')
    return out


def page_svg(page: Page, *, styles: Mapping[str, LayerStyle] | None = None, lines: Lines = Lines.LASER) -> str:
    """The SVG document of one page.

    Parameters
    ----------
    page : Page
    styles : mapping of str to LayerStyle, optional
        Colour map (default :data:`~voxfab.drawing.LAYERS`).
    lines : Lines
        ``LASER``: hairlines, no fills or images; ``PREVIEW``: visible widths, images and fills.

    Returns
    -------
    str
    """
    st_map = LAYERS if styles is None else styles
    w, h = numbers([page.width, page.height])
    out = [
        '<?xml version="1.0" encoding="UTF-8" standalone="no"?>\n',
        '<svg xmlns="http://www.w3.org/2000/svg" '
        'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" version="1.1" '
        f'width="{w}mm" height="{h}mm" viewBox="0 0 {w} {h}">\n',
    ]
    if page.title:
        out.append(f"<title>{escape(page.title, quote=False)}</title>\n")
    if lines is Lines.PREVIEW or page.artwork:
        out += _images(page)
        if page.fills:
            out += _fills(page)
    for name in page.used_layers():
        st = st_map[name]
        dash = DASH_PATTERNS[st.style]
        dash_attr = f' stroke-dasharray="{" ".join(numbers(dash))}"' if dash else ""
        inks = page.inks_of(name)
        if inks:
            # Printed art: visible widths whatever the file's lines, a halo under each ink.
            w = st.line_width(Lines.PREVIEW)
            paths = [_paths(ink.lines, page.height) for ink in inks]  # each stroked twice with a halo
            for part, width in (("halo", w + 2 * HALO), ("ink", w)):
                for i, ink in enumerate(inks):
                    color = ink.halo if part == "halo" else ink.color
                    if not color:
                        continue
                    out.append(f'<g id="{name}-{part}{i + 1}" fill="none" stroke="{color}" '
                               f'stroke-width="{numbers([width])[0]}"{dash_attr} stroke-linecap="butt" '
                               'stroke-linejoin="miter">\n')
                    out.append(paths[i])
                    out.append("</g>\n")
            continue
        width = numbers([st.line_width(lines)])[0]
        out.append(
            f'<g id="{name}" inkscape:groupmode="layer" inkscape:label="{name}" fill="none" '
            f'stroke="{st.color}" stroke-width="{width}"{dash_attr} stroke-linecap="butt" '
            'stroke-linejoin="miter">\n'
        )
        out.append(_paths(page.lines(name), page.height))
        for x, y, r in page.circles_of(name).tolist():
            cx, cy, rr = numbers([x, page.height - y, r], decimals=3)
            out.append(f'<circle cx="{cx}" cy="{cy}" r="{rr}"/>\n')
        out.append("</g>\n")
    if len(page.marks):
        pts = page.marks.points.copy()
        pts[:, 1] = page.height - pts[:, 1]
        d = polyline_text(pts, page.marks.offsets, "M%s,%s", " L%s,%s", " Z ")
        out.append('<g id="REGISTRATION" inkscape:groupmode="layer" inkscape:label="REGISTRATION" stroke="none" '
                   f'fill="#000000" fill-rule="evenodd">\n<path d="{d.rstrip()}"/>\n</g>\n')
    out.append("</svg>\n")
    return "".join(out)


def write_svg(pages: Sequence[Page], paths: Sequence[Path], *, styles: Mapping[str, LayerStyle] | None = None,
              lines: Lines = Lines.LASER) -> list[str]:
    """Write one SVG per page to ``paths`` (atomically); returns the paths written."""
    for page, path in zip(pages, paths):
        write_text(path, page_svg(page, styles=styles, lines=lines))
    return [str(p) for p in paths]
