"""DXF writer: layers CUT, MOUNTAIN, VALLEY, GRID, LABEL with straight LINE/POLYLINE entities.

R12 (the default, the safest input for laser software) is written directly as
group codes: ezdxf takes about a second per few thousand R12 POLYLINEs here,
while a 3000-face net with numbers has tens of thousands of strokes.  The file
holds a HEADER with extents and limits, LTYPE and LAYER tables and the
entities, and passes ezdxf's audit.  R12 has no ``$INSUNITS``; the units are mm.
R2000 is written with ezdxf (LWPOLYLINE, ``$INSUNITS`` = 4 for mm).
"""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from voxfab._shared.atomic import write_bytes

from ._drawing import Drawing, Sheet
from ._format import numbers, polyline_text
from ._options import DASH_PATTERNS, LAYERS, LayerStyle, LineStyle

#: DXF linetype name of each dash style.
LINETYPE_NAMES: dict[LineStyle, str] = {
    LineStyle.SOLID: "CONTINUOUS",
    LineStyle.DASHED: "DASHED",
    LineStyle.DASHDOT: "DASHDOT",
    LineStyle.DOTTED: "DOT",
}

# AutoCAD Color Index entries an RGB colour is matched against (7 prints black on white).
_ACI = {1: (255, 0, 0), 2: (255, 255, 0), 3: (0, 255, 0), 4: (0, 255, 255), 5: (0, 0, 255),
        6: (255, 0, 255), 7: (0, 0, 0), 8: (128, 128, 128), 9: (192, 192, 192)}


def aci(rgb: tuple[int, int, int]) -> int:
    """Nearest AutoCAD Color Index for an RGB colour (white maps to 7 as well)."""
    if rgb == (255, 255, 255):
        return 7
    return min(_ACI, key=lambda k: (sum((a - b) ** 2 for a, b in zip(_ACI[k], rgb)), k))


def _extents(sheet: Sheet) -> tuple[float, float, float, float]:
    pts = [lines.points for lines in sheet.layers.values() if len(lines)]
    if not pts:
        return 0.0, 0.0, sheet.width, sheet.height
    p = np.concatenate(pts)
    lo, hi = p.min(axis=0), p.max(axis=0)
    return float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])


def _pairs(*items: tuple[int, str]) -> str:
    return "".join(f"{c:>3}\n{v}\n" for c, v in items)


def sheet_dxf_r12(sheet: Sheet, styles: dict[str, LayerStyle]) -> str:
    """An R12 DXF document of one sheet (text)."""
    x0, y0, x1, y1 = numbers(_extents(sheet))
    w, h = numbers([sheet.width, sheet.height])
    out = [_pairs((0, "SECTION"), (2, "HEADER"), (9, "$ACADVER"), (1, "AC1009"),
                  (9, "$INSBASE"), (10, "0"), (20, "0"), (30, "0"),
                  (9, "$EXTMIN"), (10, x0), (20, y0), (30, "0"),
                  (9, "$EXTMAX"), (10, x1), (20, y1), (30, "0"),
                  (9, "$LIMMIN"), (10, "0"), (20, "0"),
                  (9, "$LIMMAX"), (10, w), (20, h),
                  (9, "$LUNITS"), (70, "2"),
                  (0, "ENDSEC"))]
    linetypes = sorted({styles[n].style for n in LAYERS} | {LineStyle.SOLID}, key=lambda s: s.value)
    out.append(_pairs((0, "SECTION"), (2, "TABLES"), (0, "TABLE"), (2, "LTYPE"), (70, str(len(linetypes)))))
    for ls in linetypes:
        pattern = DASH_PATTERNS[ls]
        items = [(0, "LTYPE"), (2, LINETYPE_NAMES[ls]), (70, "0"), (3, ls.value), (72, "65"),
                 (73, str(len(pattern))), (40, numbers([sum(pattern)])[0])]
        items += [(49, v) for v in numbers([x if i % 2 == 0 else -x for i, x in enumerate(pattern)])]
        out.append(_pairs(*items))
    out.append(_pairs((0, "ENDTAB"), (0, "TABLE"), (2, "LAYER"), (70, str(len(LAYERS) + 1))))
    for name in ("0",) + LAYERS:
        st = styles.get(name)
        color = str(aci(st.rgb)) if st else "7"
        ltype = LINETYPE_NAMES[st.style] if st else "CONTINUOUS"
        out.append(_pairs((0, "LAYER"), (2, name), (70, "0"), (62, color), (6, ltype)))
    out.append(_pairs((0, "ENDTAB"), (0, "ENDSEC"), (0, "SECTION"), (2, "ENTITIES")))
    for name in LAYERS:
        lines = sheet.layers[name]
        if not len(lines):
            continue
        line = (np.diff(lines.offsets) == 2) & ~lines.closed
        vertex = f"  0\nVERTEX\n  8\n{name}\n 10\n%s\n 20\n%s\n 30\n0\n"
        head = f"  0\nPOLYLINE\n  8\n{name}\n 66\n1\n 10\n0\n 20\n0\n 30\n0\n 70\n"
        first = np.where(line, f"  0\nLINE\n  8\n{name}\n 10\n%s\n 20\n%s\n 30\n0\n",
                         np.where(lines.closed, head + "1\n", head + "0\n") + vertex)
        rest = np.where(line, " 11\n%s\n 21\n%s\n 31\n0\n", vertex)
        end = np.where(line, "", f"  0\nSEQEND\n  8\n{name}\n")
        out.append(polyline_text(lines.points, lines.offsets, first, rest, end, decimals=4))
    out.append(_pairs((0, "ENDSEC"), (0, "EOF")))
    return "".join(out)


def sheet_dxf_r2000(sheet: Sheet, styles: dict[str, LayerStyle]) -> bytes:
    """An R2000 DXF document of one sheet, written by ezdxf with fixed metadata."""
    import ezdxf

    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    # No dates or random GUIDs, neither when the document is made nor when written.
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        return _r2000(sheet, styles)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed


def _r2000(sheet: Sheet, styles: dict[str, LayerStyle]) -> bytes:
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
    for name in LAYERS:
        lines = sheet.layers[name]
        if not len(lines):
            continue
        counts = np.diff(lines.offsets)
        line = (counts == 2) & ~lines.closed
        ids = [f"{h:X}" for h in range(next_handle, next_handle + len(lines))]
        next_handle += len(lines)
        common = [f"\n330\n{owner}\n100\nAcDbEntity\n  8\n{name}\n" for _ in ids]
        first = [
            (f"  0\nLINE\n  5\n{h}{c}100\nAcDbLine\n 10\n%s\n 20\n%s\n 30\n0\n" if is_line else
             f"  0\nLWPOLYLINE\n  5\n{h}{c}100\nAcDbPolyline\n 90\n{n}\n 70\n{int(cl)}\n 10\n%s\n 20\n%s\n")
            for h, c, is_line, n, cl in zip(ids, common, line.tolist(), counts.tolist(), lines.closed.tolist())
        ]
        rest = np.where(line, " 11\n%s\n 21\n%s\n 31\n0\n", " 10\n%s\n 20\n%s\n")
        chunks.append(polyline_text(lines.points, lines.offsets, np.array(first, dtype=object), rest, "",
                                    decimals=4))
    handles.reset(f"{next_handle:X}")
    x0, y0, x1, y1 = _extents(sheet)
    doc.header["$EXTMIN"] = (x0, y0, 0.0)
    doc.header["$EXTMAX"] = (x1, y1, 0.0)
    doc.header["$LIMMIN"] = (0.0, 0.0)
    doc.header["$LIMMAX"] = (sheet.width, sheet.height)
    stream = io.StringIO()
    doc.write(stream)
    text = stream.getvalue()
    marker = "  2\nENTITIES\n"
    at = text.index(marker) + len(marker)
    return doc.encode(text[:at] + "".join(chunks) + text[at:])


def write_dxf(drawing: Drawing, paths: list[Path], styles: dict[str, LayerStyle], *,
              version: str = "R12") -> list[str]:
    """Write one DXF per sheet to ``paths``; returns the paths written."""
    for sheet, path in zip(drawing.sheets, paths):
        if version == "R12":
            write_bytes(path, sheet_dxf_r12(sheet, styles).encode("ascii"))
        else:
            write_bytes(path, sheet_dxf_r2000(sheet, styles))
    return [str(p) for p in paths]
