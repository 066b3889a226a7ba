"""2D drawings: layered polylines and single-stroke text in millimetres, one backend per format.

Every flat output of voxfab (paper nets, slice plates, the net picture of the
triptych) is a :class:`Drawing`: pages of :class:`Polylines` sorted into the
layers of one table, :data:`LAYERS` (CUT, SCORE, MOUNTAIN, VALLEY, GRID, LABEL
with their colours, dash styles and visible widths), plus circles, fills and
placed raster pictures (:class:`PlacedImage`: the pictures' PDFs, a triptych on a page).
Text is single-stroke (:func:`text_polylines`), so no file needs a font.

Backends, one module each, imported on first use:

* :mod:`voxfab.drawing.svg` — SVG in mm, hairlines for lasers or visible lines for people;
* :mod:`voxfab.drawing.dxf` — DXF R2000 declaring mm (or R12 for old cutters), with extents;
* :mod:`voxfab.drawing.pdf` — true-size PDF for printing;
* :mod:`voxfab.drawing.png` — a raster preview.

:func:`write_drawing` picks the backend from the file extension.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from voxfab._shared.lazy import lazy_names
from voxfab.errors import UnknownFormatError

from ._layers import (
    DASH_PATTERNS,
    HAIRLINE,
    LAYER_PURPOSES,
    LAYERS,
    LayerStyle,
    Lines,
    LineStyle,
    aci,
    parse_colors,
)
from ._sheets import MAX_SHEET, SHEETS, parse_sheet, sheet_problem
from .dxf import DEFAULT_DXF_VERSION

if TYPE_CHECKING:
    from ._cutters import CUTTERS, Cutter, CutterMarks, clear_of_marks, cutter_area, registration_marks
    from ._font import text_polylines, text_width
    from ._legend import Legend
    from ._model import HALO, Drawing, Fill, Ink, Page, PlacedImage
    from ._polylines import Polylines

#: Names whose modules load on first use: the options of a drawing (layers, sheets) need none of them.
_LAZY = {**dict.fromkeys(("CUTTERS", "Cutter", "CutterMarks", "clear_of_marks", "cutter_area", "registration_marks"),
                         "_cutters"),
         "text_polylines": "_font", "text_width": "_font", "Legend": "_legend",
         **dict.fromkeys(("HALO", "Drawing", "Fill", "Ink", "Page", "PlacedImage"), "_model"),
         "Polylines": "_polylines"}

__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())

__all__ = [
    "CUTTERS",
    "Cutter",
    "CutterMarks",
    "clear_of_marks",
    "cutter_area",
    "registration_marks",
    "DASH_PATTERNS",
    "Drawing",
    "FORMATS",
    "Fill",
    "HALO",
    "Ink",
    "HAIRLINE",
    "LAYERS",
    "LAYER_PURPOSES",
    "LayerStyle",
    "LineStyle",
    "Legend",
    "MAX_SHEET",
    "Lines",
    "Page",
    "PlacedImage",
    "Polylines",
    "SHEETS",
    "WriteOptions",
    "aci",
    "page_paths",
    "parse_colors",
    "parse_sheet",
    "sheet_problem",
    "text_polylines",
    "text_width",
    "write_drawing",
]

#: File extensions the backends write.
FORMATS: tuple[str, ...] = (".dxf", ".pdf", ".png", ".svg")


@dataclasses.dataclass(frozen=True)
class WriteOptions:
    """How a drawing becomes files.

    Parameters
    ----------
    styles : mapping of str to LayerStyle, optional
        Colour map; default :data:`LAYERS`.
    lines : Lines
        SVG line widths: ``LASER`` hairlines or ``PREVIEW`` visible widths.
    dxf_version : str
        ``R2000`` (declares mm) or ``R12`` (old cutters).
    png_scale : float
        PNG pixels per mm.
    legend : Legend, optional
        Print a legend of the line styles on PDF and PNG pages.
    creator : str
        PDF creator field.
    """

    styles: Mapping[str, LayerStyle] | None = None
    lines: Lines = Lines.LASER
    dxf_version: str = DEFAULT_DXF_VERSION.value
    png_scale: float = 4.0
    legend: Legend | None = None
    creator: str = "voxfab"


def page_paths(path: Path, count: int, *, sep: str = ".sheet-") -> list[Path]:
    """``path`` itself for one page, else ``stem.sheet-1.ext``, ``stem.sheet-2.ext``, ...

    The word ``sheet`` in the name keeps sheet numbers apart from other numbers
    in the stem (``net-2.sheet-1.svg`` is sheet 1 of net 2).
    """
    if count == 1:
        return [path]
    return [path.with_name(f"{path.stem}{sep}{i + 1}{path.suffix}") for i in range(count)]


def write_drawing(drawing: Drawing, path: str | Path, options: WriteOptions | None = None) -> list[str]:
    """Write ``drawing`` in the format named by the extension of ``path``.

    A PDF holds every page; the other formats write one file per page, named by
    :func:`page_paths` when there are several.

    Returns
    -------
    list of str
        The paths written.

    Raises
    ------
    UnknownFormatError
        When the extension is not one of :data:`FORMATS`.
    """
    opts = options or WriteOptions()
    path = Path(path)
    ext = path.suffix.lower()
    if ext == ".pdf":
        from .pdf import write_pdf

        return write_pdf(drawing, path, styles=opts.styles, legend=opts.legend, creator=opts.creator)
    paths = page_paths(path, len(drawing.pages))
    if ext == ".svg":
        from .svg import write_svg

        return write_svg(drawing.pages, paths, styles=opts.styles, lines=opts.lines)
    if ext == ".dxf":
        from .dxf import write_dxf

        return write_dxf(drawing.pages, paths, styles=opts.styles, version=opts.dxf_version)
    if ext == ".png":
        from .png import write_png

        return sum((write_png(page, p, scale=opts.png_scale, styles=opts.styles, legend=opts.legend)
                    for page, p in zip(drawing.pages, paths)), [])
    raise UnknownFormatError(
        f"{path}: unknown drawing format {ext or '(none)'!r}; expected one of {', '.join(FORMATS)}"
    )
