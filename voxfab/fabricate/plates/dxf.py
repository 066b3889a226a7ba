"""PlateSheet → DXF through the drawing backend: R12 primitives in mm (CUT, SCORE, LABEL layers)."""

from __future__ import annotations

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike

from ._nest import PlateSheet
from ._page import sheet_page

__all__ = ["sheet_dxf", "write_dxf"]


def sheet_dxf(sheet: PlateSheet, *, version: str = "R12") -> bytes:
    """Return the DXF file of one sheet: closed cut POLYLINEs, dowel CIRCLEs, scores and labels."""
    from voxfab.drawing.dxf import page_dxf

    return page_dxf(sheet_page(sheet), version=version)


def write_dxf(sheet: PlateSheet, path: PathLike, *, version: str = "R12") -> None:
    """Write one sheet as DXF to ``path`` (atomically)."""
    write_bytes(path, sheet_dxf(sheet, version=version))
