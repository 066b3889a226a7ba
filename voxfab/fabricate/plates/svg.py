"""A plate sheet → SVG in mm through the drawing backend (hairlines, one layer per line type)."""

from __future__ import annotations

from voxfab._shared.atomic import write_text
from voxfab._shared.typing import PathLike

from ._nest import PlateSheet
from ._page import sheet_page

__all__ = ["sheet_svg", "write_svg"]


def sheet_svg(sheet: PlateSheet) -> str:
    """Return the SVG text of one sheet: layers CUT, SCORE and LABEL as hairlines."""
    from voxfab.drawing.svg import page_svg

    return page_svg(sheet_page(sheet))


def write_svg(sheet: PlateSheet, path: PathLike) -> None:
    """Write one sheet as SVG to ``path`` (atomically)."""
    write_text(path, sheet_svg(sheet))
