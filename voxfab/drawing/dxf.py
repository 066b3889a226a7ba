"""DXF backend: one layer per drawing layer, straight LINE/(LW)POLYLINE entities and CIRCLEs.

R2000 is the default: it declares its units (``$INSUNITS`` = 4, millimetres, and
``$MEASUREMENT`` = 1, metric), so a laser program does not read the geometry as
inches.  It gets its tables from ezdxf and its entities (LINE, LWPOLYLINE) as
group codes.  R12 (AC1009) stays an option for old cutters: it has no unit
variable, so its numbers are millimetres by convention only.  It is written
directly as group codes: ezdxf takes about a second per few thousand R12
POLYLINEs here, while a 3000-face net with numbers has tens of thousands of
strokes.  Both versions carry ``$EXTMIN``/``$EXTMAX`` of the geometry, which
some laser software asks for, and pass ezdxf's audit.
"""

from __future__ import annotations

import io
from collections.abc import Mapping, Sequence
from enum import Enum
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from voxfab._shared.atomic import write_bytes
from voxfab._shared.options import option

from ._format import numbers, polyline_text
from ._layers import DASH_PATTERNS, LAYERS, LayerStyle, LineStyle, aci

if TYPE_CHECKING:
    from ._model import Page

__all__ = ["DEFAULT_DXF_VERSION", "DxfVersion", "LINETYPE_NAMES", "dxf_version_option", "page_dxf", "page_dxf_r12",
           "page_dxf_r2000", "write_dxf"]


class DxfVersion(Enum):
    """DXF versions written."""

    R12 = "R12"
    R2000 = "R2000"


#: The version written unless asked otherwise: the first that declares millimetres.
DEFAULT_DXF_VERSION = DxfVersion.R2000


def dxf_version_option() -> str:
    """The ``dxf_version`` option, declared once for every artefact that writes DXF (nets, slice sheets)."""
    return option(DEFAULT_DXF_VERSION.value, help="DXF version: R2000 declares mm ($INSUNITS = 4, $MEASUREMENT = "
                  "1); R12 for old cutters (no unit variable, mm by convention)",
                  choices=tuple(v.value for v in DxfVersion))


#: DXF linetype name of each dash style.
LINETYPE_NAMES: dict[LineStyle, str] = {
    LineStyle.SOLID: "CONTINUOUS",
    LineStyle.DASHED: "DASHED",
    LineStyle.DASHDOT: "DASHDOT",
    LineStyle.DOTTED: "DOT",
}


def _pairs(*items: tuple[int, str]) -> str:
    return "".join(f"{c:>3}\n{v}\n" for c, v in items)


def _circles_r12(page: Page, name: str) -> str:
    c = page.circles_of(name)
    if not c.shape[0]:
        return ""
    values = numbers(c, decimals=4)
    head = f"  0\nCIRCLE\n  8\n{name}\n"
    return "".join(f"{head} 10\n{x}\n 20\n{y}\n 30\n0\n 40\n{r}\n"
                   for x, y, r in zip(values[0::3], values[1::3], values[2::3]))


def page_dxf_r12(page: Page, styles: Mapping[str, LayerStyle] | None = None) -> str:
    """An R12 DXF document of one page (text)."""
    st_map = LAYERS if styles is None else styles
    x0, y0, x1, y1 = numbers(page.extents())
    w, h = numbers([page.width, page.height])
    out = [_pairs((0, "SECTION"), (2, "HEADER"), (9, "$ACADVER"), (1, "AC1009"),
                  (9, "$INSBASE"), (10, "0"), (20, "0"), (30, "0"),
                  (9, "$EXTMIN"), (10, x0), (20, y0), (30, "0"),
                  (9, "$EXTMAX"), (10, x1), (20, y1), (30, "0"),
                  (9, "$LIMMIN"), (10, "0"), (20, "0"),
                  (9, "$LIMMAX"), (10, w), (20, h),
                  (9, "$LUNITS"), (70, "2"),
                  (0, "ENDSEC"))]
    linetypes = sorted({st_map[n].style for n in LAYERS} | {LineStyle.SOLID}, key=lambda s: s.value)
    out.append(_pairs((0, "SECTION"), (2, "TABLES"), (0, "TABLE"), (2, "LTYPE"), (70, str(len(linetypes)))))
    for ls in linetypes:
        pattern = DASH_PATTERNS[ls]
        items = [(0, "LTYPE"), (2, LINETYPE_NAMES[ls]), (70, "0"), (3, ls.value), (72, "65"),
                 (73, str(len(pattern))), (40, numbers([sum(pattern)])[0])]
        items += [(49, v) for v in numbers([x if i % 2 == 0 else -x for i, x in enumerate(pattern)])]
        out.append(_pairs(*items))
    out.append(_pairs((0, "ENDTAB"), (0, "TABLE"), (2, "LAYER"), (70, str(len(LAYERS) + 1))))
    for name in ("0", *LAYERS):
        st = st_map.get(name)
        color = str(aci(st.rgb)) if st else "7"
        ltype = LINETYPE_NAMES[st.style] if st else "CONTINUOUS"
        out.append(_pairs((0, "LAYER"), (2, name), (70, "0"), (62, color), (6, ltype)))
    out.append(_pairs((0, "ENDTAB"), (0, "ENDSEC"), (0, "SECTION"), (2, "ENTITIES")))
    for name in page.used_layers():
        lines = page.lines(name)
        line = (np.diff(lines.offsets) == 2) & ~lines.closed
        vertex = f"  0\nVERTEX\n  8\n{name}\n 10\n%s\n 20\n%s\n 30\n0\n"
        head = f"  0\nPOLYLINE\n  8\n{name}\n 66\n1\n 10\n0\n 20\n0\n 30\n0\n 70\n"
        first = np.where(line, f"  0\nLINE\n  8\n{name}\n 10\n%s\n 20\n%s\n 30\n0\n",
                         np.where(lines.closed, head + "1\n", head + "0\n") + vertex)
        rest = np.where(line, " 11\n%s\n 21\n%s\n 31\n0\n", vertex)
        end = np.where(line, "", f"  0\nSEQEND\n  8\n{name}\n")
        out.append(polyline_text(lines.points, lines.offsets, first, rest, end, decimals=4))
        out.append(_circles_r12(page, name))
    out.append(_pairs((0, "ENDSEC"), (0, "EOF")))
    return "".join(out)


def page_dxf_r2000(page: Page, styles: Mapping[str, LayerStyle] | None = None) -> bytes:
    """An R2000 DXF document of one page, with ezdxf's tables and fixed metadata."""
    import ezdxf

    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    # No dates or random GUIDs, neither when the document is made nor when written.
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        return _r2000(page, LAYERS if styles is None else styles)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed


def _r2000(page: Page, styles: Mapping[str, LayerStyle]) -> bytes:
    import ezdxf

    doc = ezdxf.new("R2000")
    doc.units = 4  # $INSUNITS: millimetres
    doc.header["$MEASUREMENT"] = 1
    for ls, ltname in LINETYPE_NAMES.items():
        pattern = DASH_PATTERNS[ls]
        if pattern and ltname not in doc.linetypes:
            doc.linetypes.add(
                ltname, [sum(pattern)] + [x if i % 2 == 0 else -x for i, x in enumerate(pattern)],
                description=ls.value,
            )
    for name in LAYERS:
        st = styles[name]
        doc.layers.add(name, color=aci(st.rgb), linetype=LINETYPE_NAMES[st.style])
    # ezdxf makes the tables and objects; the entities are written directly as
    # group codes (ezdxf needs about 9 s for the 30,000 strokes of a 3000-face net).
    owner = doc.modelspace().block_record_handle
    handles = doc.entitydb.handles
    next_handle = int(str(handles), 16)
    chunks = []
    for name in page.used_layers():
        lines = page.lines(name)
        common = f"\n330\n{owner}\n100\nAcDbEntity\n  8\n{name}\n"
        if len(lines):
            counts = np.diff(lines.offsets)
            line = (counts == 2) & ~lines.closed
            ids = [f"{h:X}" for h in range(next_handle, next_handle + len(lines))]
            next_handle += len(lines)
            first = [
                (f"  0\nLINE\n  5\n{h}{common}100\nAcDbLine\n 10\n%s\n 20\n%s\n 30\n0\n" if is_line else
                 f"  0\nLWPOLYLINE\n  5\n{h}{common}100\nAcDbPolyline\n 90\n{n}\n 70\n{int(cl)}\n 10\n%s\n 20\n%s\n")
                for h, is_line, n, cl in zip(ids, line.tolist(), counts.tolist(), lines.closed.tolist())
            ]
            rest = np.where(line, " 11\n%s\n 21\n%s\n 31\n0\n", " 10\n%s\n 20\n%s\n")
            chunks.append(polyline_text(lines.points, lines.offsets, np.array(first, dtype=object), rest, "",
                                        decimals=4))
        c = page.circles_of(name)
        values = numbers(c, decimals=4)
        for x, y, r in zip(values[0::3], values[1::3], values[2::3]):
            chunks.append(f"  0\nCIRCLE\n  5\n{next_handle:X}{common}100\nAcDbCircle\n"
                          f" 10\n{x}\n 20\n{y}\n 30\n0\n 40\n{r}\n")
            next_handle += 1
    handles.reset(f"{next_handle:X}")
    x0, y0, x1, y1 = page.extents()
    # ezdxf copies the modelspace's extents and limits into the header when writing.
    msp = doc.modelspace()
    msp.dxf.extmin = (x0, y0, 0.0)
    msp.dxf.extmax = (x1, y1, 0.0)
    msp.dxf.limmin = (0.0, 0.0)
    msp.dxf.limmax = (page.width, page.height)
    stream = io.StringIO()
    doc.write(stream)
    text = stream.getvalue()
    marker = "  2\nENTITIES\n"
    at = text.index(marker) + len(marker)
    return doc.encode(text[:at] + "".join(chunks) + text[at:])


def page_dxf(page: Page, *, styles: Mapping[str, LayerStyle] | None = None,
             version: DxfVersion | str = DEFAULT_DXF_VERSION) -> bytes:
    """The DXF file of one page in ``version`` (R2000 by default, or R12), as bytes."""
    if DxfVersion(version) is DxfVersion.R12:
        return page_dxf_r12(page, styles).encode("ascii")
    return page_dxf_r2000(page, styles)


def write_dxf(pages: Sequence[Page], paths: Sequence[Path], *, styles: Mapping[str, LayerStyle] | None = None,
              version: DxfVersion | str = DEFAULT_DXF_VERSION) -> list[str]:
    """Write one DXF per page to ``paths`` (atomically); returns the paths written."""
    for page, path in zip(pages, paths):
        write_bytes(path, page_dxf(page, styles=styles, version=version))
    return [str(p) for p in paths]
