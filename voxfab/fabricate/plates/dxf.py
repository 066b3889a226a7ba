"""PlateSheet → DXF through the drawing backend: straight primitives in mm (CUT, SCORE, LABEL layers)."""

from __future__ import annotations

from voxfab._shared.atomic import write_bytes
from voxfab._shared.typing import PathLike
from voxfab.drawing.dxf import DEFAULT_DXF_VERSION, page_dxf

from ._nest import PlateSheet
from ._page import sheet_page

__all__ = ["sheet_dxf", "write_dxf"]


def sheet_dxf(sheet: PlateSheet, *, version: str = DEFAULT_DXF_VERSION.value) -> bytes:
    """Return the DXF file of one sheet (R2000 in mm, or R12): closed cut polylines, dowel CIRCLEs, scores
    and labels."""

    return page_dxf(sheet_page(sheet), version=version)


def write_dxf(sheet: PlateSheet, path: PathLike, *, version: str = DEFAULT_DXF_VERSION.value) -> None:
    """Write one sheet as DXF to ``path`` (atomically)."""
    write_bytes(path, sheet_dxf(sheet, version=version))
