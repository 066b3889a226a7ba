"""PDF backend for printing on paper: one true-size page per drawing page, no dates.

The file is written directly (a catalog, one page and one compressed content
stream per page, and an info dictionary without creation date), so the same
drawing gives the same bytes.  Lines have the layers' visible widths so a home
printer shows them clearly; placed images are painted first, losslessly
(Flate-compressed RGB image objects), then fills, then lines; an optional
legend names the line styles along the bottom edge.
"""

from __future__ import annotations

import zlib
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from voxfab._shared.atomic import write_bytes

from ._format import numbers, polyline_text
from ._layers import DASH_PATTERNS, LAYERS, LayerStyle, Lines
from ._legend import Legend, legend_layers
from ._model import HALO, Drawing, Page, PlacedImage
from ._polylines import Polylines

__all__ = ["MM", "pdf_document", "page_content", "write_pdf"]

#: PDF points per mm.
MM = 72.0 / 25.4
# Bezier handle length of a quarter circle, as a fraction of the radius.
_KAPPA = 0.5522847498


def _path_ops(lines: Polylines) -> str:
    if not len(lines):
        return ""
    ends = np.where(lines.closed, "h\n", "")
    return polyline_text(lines.points, lines.offsets, "%s %s m\n", "%s %s l\n", ends)


def _circle_ops(circles: np.ndarray) -> str:
    out = []
    for x, y, r in circles.tolist():
        k = _KAPPA * r
        pts = [(x + r, y), (x + r, y + k), (x + k, y + r), (x, y + r), (x - k, y + r), (x - r, y + k), (x - r, y),
               (x - r, y - k), (x - k, y - r), (x, y - r), (x + k, y - r), (x + r, y - k), (x + r, y)]
        v = numbers(np.array(pts), decimals=3)
        out.append(f"{v[0]} {v[1]} m\n")
        for i in range(2, 26, 6):
            out.append(" ".join(v[i:i + 6]) + " c\n")
        out.append("h\n")
    return "".join(out)


def _hex_rgb(c: str) -> tuple[int, int, int]:
    return int(c[1:3], 16), int(c[3:5], 16), int(c[5:7], 16)


def _rgb(rgb: tuple[int, int, int]) -> str:
    return " ".join(numbers([c / 255.0 for c in rgb], decimals=3))


def page_content(page: Page, *, styles: Mapping[str, LayerStyle] | None = None, legend: Legend | None = None) -> bytes:
    """The content stream of one page (uncompressed), in mm through a scaling matrix."""
    st_map = LAYERS if styles is None else styles
    extra = legend_layers(page, legend) if legend else {}
    out = [f"q {MM:.6f} 0 0 {MM:.6f} 0 0 cm 1 J 1 j\n"]
    for i, image in enumerate(page.images):
        w, h, x, y = numbers([image.width, image.height, image.x, image.y])
        out.append(f"q {w} 0 0 {h} {x} {y} cm /Im{i} Do Q\n")
    for fill in page.fills:
        if len(fill.rings) and fill.colors:  # each ring in its own colour: one path per colour
            colors = np.array(fill.colors)
            for c in dict.fromkeys(fill.colors):
                rings = fill.rings.select(colors == c)
                out.append(f"{_rgb(_hex_rgb(c))} rg\n{_path_ops(rings)}{'f' if fill.nonzero else 'f*'}\n")
        elif len(fill.rings):
            out.append(f"{_rgb(fill.rgb)} rg\n{_path_ops(fill.rings)}{'f' if fill.nonzero else 'f*'}\n")
    for name in LAYERS:
        st = st_map[name]
        dash = " ".join(numbers(DASH_PATTERNS[st.style]))
        inks = page.inks_of(name)
        w = st.line_width(Lines.PREVIEW)
        # Every halo first, so no halo covers another ink's line where two meet.
        ops = [_path_ops(i.lines) for i in inks or ()]  # each ink's path, stroked twice with a halo
        strokes = [(i.halo_rgb, w + 2 * HALO, o) for i, o in zip(inks or (), ops) if i.halo]
        for rgb, width, path in strokes + [(i.rgb, w, o) for i, o in zip(inks or (), ops)]:
            out.append(f"{_rgb(rgb)} RG {numbers([width])[0]} w [{dash}] 0 d\n{path}S\n")
        own = Polylines.empty() if inks else page.lines(name)
        lines = Polylines.concat([own, extra.get(name, Polylines.empty())])
        circles = page.circles_of(name)
        if not len(lines) and not circles.shape[0]:
            continue
        width = numbers([st.line_width(Lines.PREVIEW)])[0]
        out.append(f"{_rgb(st.rgb)} RG {width} w [{dash}] 0 d\n")
        out.append(_path_ops(lines) + _circle_ops(circles) + "S\n")
    if len(page.marks):
        out.append(f"0 0 0 rg\n{_path_ops(page.marks)}f*\n")
    out.append("Q\n")
    return "".join(out).encode("ascii")


def _pdf_text(text: str) -> str:
    safe = "".join(c for c in text if 32 <= ord(c) < 127)
    return "(" + safe.replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)") + ")"


def _image_object(image: PlacedImage) -> bytes:
    rows, cols = image.pixels.shape[:2]
    data = zlib.compress(image.pixels.tobytes(), 6)
    head = (f"<< /Type /XObject /Subtype /Image /Width {cols} /Height {rows} /ColorSpace /DeviceRGB "
            f"/BitsPerComponent 8 /Filter /FlateDecode /Length {len(data)} >>\nstream\n")
    return head.encode("ascii") + data + b"\nendstream"


def pdf_document(drawing: Drawing, *, styles: Mapping[str, LayerStyle] | None = None, legend: Legend | None = None,
                 creator: str = "voxfab") -> bytes:
    """A PDF with one true-size page per page of ``drawing``."""
    n = len(drawing.pages)
    # 1: catalog, 2: pages, 3: info, then per page a page object, its content and its images.
    firsts = [4 + sum(2 + len(p.images) for p in drawing.pages[:i]) for i in range(n)]
    objects: list[bytes] = []
    kids = " ".join(f"{k} 0 R" for k in firsts)
    objects.append(b"<< /Type /Catalog /Pages 2 0 R >>")
    objects.append(f"<< /Type /Pages /Kids [{kids}] /Count {n} >>".encode("ascii"))
    objects.append(f"<< /Title {_pdf_text(drawing.title)} /Producer (voxfab) /Creator {_pdf_text(creator)} >>"
                   .encode("ascii"))
    for first, page in zip(firsts, drawing.pages):
        w, h = numbers([page.width * MM, page.height * MM], decimals=3)
        xobjects = " ".join(f"/Im{i} {first + 2 + i} 0 R" for i in range(len(page.images)))
        resources = f"<< /XObject << {xobjects} >> >>" if page.images else "<< >>"
        objects.append(
            f"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {w} {h}] /Contents {first + 1} 0 R "
            f"/Resources {resources} >>".encode("ascii")
        )
        data = zlib.compress(page_content(page, styles=styles, legend=legend), 6)
        objects.append(
            f"<< /Length {len(data)} /Filter /FlateDecode >>\nstream\n".encode("ascii") + data + b"\nendstream"
        )
        objects += [_image_object(image) for image in page.images]
    out = bytearray(b"%PDF-1.4\n%\xe2\xe3\xcf\xd3\n")
    offsets = []
    for i, body in enumerate(objects):
        offsets.append(len(out))
        out += f"{i + 1} 0 obj\n".encode("ascii") + body + b"\nendobj\n"
    xref = len(out)
    out += f"xref\n0 {len(objects) + 1}\n0000000000 65535 f \n".encode("ascii")
    out += "".join(f"{o:010d} 00000 n \n" for o in offsets).encode("ascii")
    out += f"trailer\n<< /Size {len(objects) + 1} /Root 1 0 R /Info 3 0 R >>\nstartxref\n{xref}\n%%EOF\n".encode("ascii")
    return bytes(out)


def write_pdf(drawing: Drawing, path: Path, *, styles: Mapping[str, LayerStyle] | None = None,
              legend: Legend | None = None, creator: str = "voxfab") -> list[str]:
    """Write all pages of ``drawing`` to one PDF (atomically); returns the path written."""
    write_bytes(path, pdf_document(drawing, styles=styles, legend=legend, creator=creator))
    return [str(path)]
