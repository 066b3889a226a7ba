"""Sheet → DXF R12 with layers CUT (red), SCORE (blue) and ENGRAVE (black/white).

Only R12 primitives are written (closed and open 2D POLYLINEs, CIRCLEs), in
mm, which the oldest laser software reads.  Metadata dates and GUIDs are
fixed so the same sheet always gives the same bytes.
"""

from __future__ import annotations

import contextlib
import io
import logging
import re
from collections.abc import Iterator

import numpy as np
import numpy.typing as npt

from voxfab._shared.atomic import write_text
from voxfab._shared.typing import PathLike
from voxfab.errors import FabricationError

from ._nest import Sheet

__all__ = ["LAYERS", "sheet_dxf", "write_dxf"]

#: Layer name → ACI colour (1 red, 5 blue, 7 black/white).
LAYERS: dict[str, int] = {"CUT": 1, "SCORE": 5, "ENGRAVE": 7}


@contextlib.contextmanager
def _quiet_fixed_ezdxf() -> Iterator[None]:
    """Fixed metadata while writing; no R12 units warning from ``ezdxf.new``."""
    import ezdxf

    log = logging.getLogger("ezdxf")
    level, fixed = log.level, ezdxf.options.write_fixed_meta_data_for_testing
    log.setLevel(logging.ERROR)
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        log.setLevel(level)
        ezdxf.options.write_fixed_meta_data_for_testing = fixed


def _num(v: float) -> str:
    # rounding kills -0.0 and 1e-15 noise, so equal inputs give equal text
    return repr(round(float(v), 6) + 0.0)


class _Entities:
    """Writes R12 ENTITIES group codes directly, numbering handles from ``seed``.

    ezdxf builds a VERTEX object per point, which costs about a millisecond per
    polyline; plain text with the same group codes is read back identically.
    """

    def __init__(self, seed: int) -> None:
        self.handle = seed
        self.out: list[str] = []

    def _h(self) -> str:
        h = f"{self.handle:X}"
        self.handle += 1
        return h

    def polyline(self, xy: npt.NDArray[np.float64], layer: str, *, closed: bool) -> None:
        head, tail = self._h(), self._h()
        out = self.out
        out.append(f"  0\nPOLYLINE\n  5\n{head}\n  8\n{layer}\n 66\n1\n 10\n0.0\n 20\n0.0\n 30\n0.0\n 70\n{1 if closed else 0}\n")
        for x, y in xy:
            out.append(f"  0\nVERTEX\n  5\n{self._h()}\n  8\n{layer}\n 10\n{_num(x)}\n 20\n{_num(y)}\n 30\n0.0\n 70\n0\n")
        out.append(f"  0\nSEQEND\n  5\n{tail}\n  8\n{layer}\n")

    def circle(self, x: float, y: float, r: float, layer: str) -> None:
        self.out.append(
            f"  0\nCIRCLE\n  5\n{self._h()}\n  8\n{layer}\n 10\n{_num(x)}\n 20\n{_num(y)}\n 30\n0.0\n 40\n{_num(r)}\n"
        )


_ENTITIES = "  0\nSECTION\n  2\nENTITIES\n  0\nENDSEC\n"
_HANDSEED = re.compile(r"\$HANDSEED\n  5\n([0-9A-Fa-f]+)\n")


def sheet_dxf(sheet: Sheet) -> str:
    """Return the DXF R12 text of one sheet.

    Cut rings become closed POLYLINEs, dowel holes CIRCLEs, scores and label
    strokes open POLYLINEs.  Coordinates are in mm with the sheet's lower-left
    corner at the origin.  The header and tables come from ezdxf; the
    entities are written directly (see :class:`_Entities`).
    """
    import ezdxf
    from ezdxf.document import CREATED_BY_EZDXF

    with _quiet_fixed_ezdxf():
        doc = ezdxf.new("R12")
        doc.ezdxf_metadata()[CREATED_BY_EZDXF] = "ezdxf"
        for name, color in LAYERS.items():
            doc.layers.add(name, color=color)
        doc.header["$EXTMIN"] = (0.0, 0.0, 0.0)
        doc.header["$EXTMAX"] = (float(sheet.width), float(sheet.height), 0.0)
        doc.header["$LIMMIN"] = (0.0, 0.0)
        doc.header["$LIMMAX"] = (float(sheet.width), float(sheet.height))
        buf = io.StringIO()
        doc.write(buf)
    text = buf.getvalue()
    seed = _HANDSEED.search(text)
    if seed is None or text.count(_ENTITIES) != 1:  # pragma: no cover - guards an ezdxf change
        raise FabricationError("unexpected DXF layout from ezdxf: cannot add the sheet's entities")
    ents = _Entities(int(seed.group(1), 16))
    for part in sheet.parts:
        for ring in part.cut:
            ents.polyline(ring[:-1], "CUT", closed=True)
        for x, y, r in part.circles:
            ents.circle(x, y, r, "CUT")
        for line in part.score:
            ents.polyline(line, "SCORE", closed=False)
        for line in part.engrave:
            ents.polyline(line, "ENGRAVE", closed=False)
    body = "  0\nSECTION\n  2\nENTITIES\n" + "".join(ents.out) + "  0\nENDSEC\n"
    text = text.replace(_ENTITIES, body)
    return _HANDSEED.sub(f"$HANDSEED\n  5\n{ents.handle:X}\n", text, count=1)


def write_dxf(sheet: Sheet, path: PathLike) -> None:
    """Write one sheet as DXF R12 to ``path`` (atomically)."""
    write_text(path, sheet_dxf(sheet))
