"""PDF writer for printing on paper: one page per sheet, true size, no dates.

The file is written directly (a catalog, one page and one compressed content
stream per sheet, and an info dictionary without creation date), so the same
drawing gives the same bytes.  Lines are 0.2 mm wide so a home printer shows
them clearly; a legend names the line styles under the title.
"""

from __future__ import annotations

import zlib
from pathlib import Path

import numpy as np

from voxfab._shared.atomic import write_bytes

from .._font import text_polylines
from .._polylines import Polylines
from ._drawing import Drawing, Sheet
from ._format import numbers, polyline_text
from ._options import DASH_PATTERNS, LAYERS, LayerStyle

MM = 72.0 / 25.4
#: Printed line widths, mm.
LINE_WIDTH = 0.2
LABEL_WIDTH = 0.15

_LEGEND = (("CUT", "CUT"), ("MOUNTAIN", "MOUNTAIN"), ("VALLEY", "VALLEY"), ("GRID", "GRID"))


def _path_ops(lines: Polylines) -> str:
    if not len(lines):
        return ""
    ends = np.where(lines.closed, "h\n", "")
    return polyline_text(lines.points, lines.offsets, "%s %s m\n", "%s %s l\n", ends) + "S\n"


def _legend(sheet: Sheet, styles: dict[str, LayerStyle], y: float) -> dict[str, Polylines]:
    """Short sample lines with their names, right-aligned on the title baseline."""
    out: dict[str, list[Polylines]] = {}
    x = sheet.width - 10.0
    h = 2.0
    for layer, name in reversed(_LEGEND):
        if not len(sheet.layers[layer]):
            continue
        width = (len(name) - 1) * h + h * 4 / 6
        x -= width
        out.setdefault("LABEL", []).append(text_polylines([name], [(x, y)], [(1.0, 0.0)], h))
        x -= 9.0
        out.setdefault(layer, []).append(Polylines.from_segments([(x, y + h / 2)], [(x + 8.0, y + h / 2)]))
        x -= 4.0
    return {k: Polylines.concat(v) for k, v in out.items()}


def sheet_content(sheet: Sheet, styles: dict[str, LayerStyle], *, legend: bool = True) -> bytes:
    """The page content stream of one sheet (uncompressed)."""
    extra = _legend(sheet, styles, 11.0) if legend else {}
    out = [f"q {MM:.6f} 0 0 {MM:.6f} 0 0 cm 1 J 1 j\n"]
    for name in LAYERS:
        lines = Polylines.concat([sheet.layers[name], extra.get(name, Polylines.empty())])
        if not len(lines):
            continue
        st = styles[name]
        r, g, b = (numbers([c / 255.0], decimals=3)[0] for c in st.rgb)
        dash = " ".join(numbers(DASH_PATTERNS[st.style]))
        width = LABEL_WIDTH if name == "LABEL" else LINE_WIDTH
        out.append(f"{r} {g} {b} RG {width} w [{dash}] 0 d\n")
        out.append(_path_ops(lines))
    out.append("Q\n")
    return "".join(out).encode("ascii")


def pdf_document(drawing: Drawing, styles: dict[str, LayerStyle], *, title: str = "") -> bytes:
    """A PDF with one true-size page per sheet."""
    n = len(drawing.sheets)
    objects: list[bytes] = []
    # 1: catalog, 2: pages, 3: info, then per sheet a page and its content.
    kids = " ".join(f"{4 + 2 * i} 0 R" for i in range(n))
    objects.append(b"<< /Type /Catalog /Pages 2 0 R >>")
    objects.append(f"<< /Type /Pages /Kids [{kids}] /Count {n} >>".encode("ascii"))
    safe = "".join(c for c in title if 32 <= ord(c) < 127).replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)")
    objects.append(f"<< /Title ({safe}) /Producer (voxfab) /Creator (voxfab net) >>".encode("ascii"))
    for i, sheet in enumerate(drawing.sheets):
        w, h = numbers([sheet.width * MM, sheet.height * MM], decimals=3)
        objects.append(
            f"<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {w} {h}] /Contents {5 + 2 * i} 0 R "
            "/Resources << >> >>".encode("ascii")
        )
        data = zlib.compress(sheet_content(sheet, styles), 6)
        objects.append(
            f"<< /Length {len(data)} /Filter /FlateDecode >>\nstream\n".encode("ascii") + data + b"\nendstream"
        )
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


def write_pdf(drawing: Drawing, path: Path, styles: dict[str, LayerStyle], *, title: str = "") -> list[str]:
    """Write all sheets as pages of one PDF; returns the path written."""
    write_bytes(path, pdf_document(drawing, styles, title=title))
    return [str(path)]
