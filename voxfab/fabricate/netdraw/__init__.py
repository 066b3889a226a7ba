"""Net drawings: cut outlines, mountain/valley folds, glue tabs and seam labels as SVG, DXF, PDF and PNG.

A net from :mod:`voxfab.unfold` becomes a sheet that a laser cutter or a home
printer takes as is: one closed cut outline per piece, folds typed as seen from
outside, one non-overlapping glue tab per seam, a matching single-stroke label
(a short code, :mod:`._labels`) on both edges of every seam, and a title with
the shape's name, face size and seed.  Labels are at least 2 mm tall and tabs
at least 3 mm deep; smaller
faces are refused with the smallest face size that works.  A net that does not
fit its sheet is refused too, naming the largest face size at which it fits and
the smallest sheet that takes it; pieces (``pieces="auto"``) are packed on as
few sheets as possible.

Public API: :func:`net_files` (the whole job of ``voxfab net``: search,
validation, files), :func:`net_gallery` (distinct nets ordered by fit, for the
studio), :func:`find_sheet_nets` (shape → nets that fit the sheet),
:func:`draw_net` and :func:`draw_pieces` (nets → :class:`NetDrawing`),
:func:`write_net_drawing` (draw and write), :func:`save_drawing` (write a drawn net),
:func:`drawable_area` (the part of a sheet pieces may take), and :func:`fabricate_net`, the pipeline of the
recipe output ``net``.  Heavy libraries (shapely,
ezdxf, scipy, rectpack) load only when a drawing is made.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING, Any

from voxfab._shared.lazy import lazy_names
from voxfab.drawing import LayerStyle, LineStyle, parse_colors
from voxfab.fabricate._outputs import Artefact, OutputFile

from ._net_options import NetOptions, SheetNets
from ._options import SHEETS, DrawingOptions, parse_sheet

if TYPE_CHECKING:
    from voxfab.shape import VoxelShape
    from voxfab.unfold import Net

    from ._drawing import NetDrawing
    from ._fit import FaceSizeError
    from ._gallery import (
        Gallery,
        GalleryNet,
        fit_and_placement,
        gallery_face_size,
        gallery_json,
        gallery_options,
        net_gallery,
        net_layout,
    )
    from ._pipeline import NetFiles, check_request, net_files, parse_box, search_nets
    from ._sheets import SheetFitError, drawable_area

#: Names whose modules load on first use, so that ``voxfab net`` reads its options without the search,
#: the sheets and the drawing code (and shapely behind it).
_LAZY = {"NetDrawing": "_drawing", "FaceSizeError": "_fit",
         **dict.fromkeys(("NetFiles", "check_request", "net_files", "parse_box", "search_nets"), "_pipeline"),
         **dict.fromkeys(("Gallery", "GalleryNet", "fit_and_placement", "gallery_face_size", "gallery_json",
                          "gallery_options", "net_gallery", "net_layout"), "_gallery"),
         "SheetFitError": "_sheets", "drawable_area": "_sheets"}

__getattr__, __dir__ = lazy_names(__name__, _LAZY, globals())

__all__ = [
    "SHEETS",
    "NetDrawing",
    "DrawingOptions",
    "LayerStyle",
    "LineStyle",
    "DrawingResult",
    "NetOptions",
    "SheetFitError",
    "SheetNets",
    "draw_net",
    "draw_pieces",
    "drawable_area",
    "find_sheet_nets",
    "FaceSizeError",
    "NetFiles",
    "check_request",
    "net_files",
    "parse_box",
    "search_nets",
    "Gallery",
    "GalleryNet",
    "gallery_json",
    "gallery_options",
    "net_gallery",
    "net_layout",
    "fit_and_placement",
    "gallery_face_size",
    "drawing_formats",
    "fabricate_net",
    "parse_colors",
    "parse_sheet",
    "save_drawing",
    "write_net_drawing",
]

_DEFAULTS = DrawingOptions()


def shape_colours(shape: Any, filled: bool = False) -> tuple[Any, Any]:
    """``(grid, colours)`` of a :class:`~voxfab.shape.VoxelShape` (its colours, None when uncoloured) or of a
    bool grid (None); with ``filled``, the grid's enclosed cavities filled (a net of the outer surface)."""
    from voxfab.shape import VoxelShape, fill_cavities

    grid, colours = (shape.grid, shape.colours) if isinstance(shape, VoxelShape) else (shape, None)
    if not filled:
        return grid, colours
    grid = fill_cavities(grid)
    return grid, (None if colours is None else colours.fitted(grid))


def draw_net(shape: Any, net: Net, *, options: DrawingOptions | None = None, name: str = "") -> NetDrawing:
    """Lay ``net`` (a net of ``shape``, a VoxelShape or a bool grid) out on sheets, each face in its voxel's
    colour when the shape has colours; see :func:`._drawing.draw_net`."""
    from ._drawing import draw_net as _draw

    grid, colours = shape_colours(shape)
    return _draw(grid, net, options=options, name=name, colours=colours)


def draw_pieces(shape: Any, pieces: list[Net], *, options: DrawingOptions | None = None, name: str = "",
                placement: Any = None) -> NetDrawing:
    """Pack the pieces of a net on as few sheets as possible (or as ``placement`` puts them); see :func:`._drawing.draw_pieces`."""
    from ._drawing import draw_pieces as _draw

    grid, colours = shape_colours(shape)
    return _draw(grid, pieces, options=options, name=name, placement=placement, colours=colours)


def find_sheet_nets(grid: Any, options: DrawingOptions, *, rng: int, pieces: str = "one", count: int = 1,
                    **search: Any) -> SheetNets:
    """Nets of ``grid`` that fit the sheet of ``options``; see :func:`._fit.find_sheet_nets`."""
    from ._fit import find_sheet_nets as _find

    return _find(grid, options, rng=rng, pieces=pieces, count=count, **search)


def drawing_formats() -> list[str]:
    """File extensions :func:`write_net_drawing` understands."""
    from ._writers import drawing_formats as _formats

    return _formats()


@dataclasses.dataclass(frozen=True)
class DrawingResult:
    """What writing a net drawing did.

    Attributes
    ----------
    files : list of str
        Paths written.
    report : list of str
        Face size, sheets and their fill, tabs, labels and folds.
    warnings : list of str
        The lines a maker must read before making it (a net split into pieces,
        seams without tabs); also the last lines of ``report``.
    face_size : float
        Face edge, mm.
    fill : list of float
        Share of each sheet covered by paper, 0 to 1.
    seams_without_tab : int
        Seams drawn without room for a glue tab (marked for tape), as the report and warnings count them.
    """

    files: list[str]
    report: list[str]
    warnings: list[str]
    face_size: float
    fill: list[float]
    seams_without_tab: int = 0


def write_net_drawing(shape: Any, nets: Net | list[Net], path: str | Path, options: DrawingOptions, *,
                      title: str = "") -> DrawingResult:
    """Draw a net (or the pieces of one, packed) of ``grid`` and write it to ``path``.

    The extension picks the format: ``.svg`` and ``.dxf`` are laser files (one
    per sheet, named ``NAME.sheet-N.ext`` when there are several), ``.pdf`` and
    ``.png`` are for people (visible lines, shaded tabs, a legend).

    Parameters
    ----------
    shape : VoxelShape or (X, Y, Z) bool array_like
        The shape the net unfolds (cavities filled for a net of the outer surface); a coloured
        shape prints each face in its voxel's colour.
    nets : Net or list of Net
        A net, or the pieces of a several-piece unfolding.
    path : str or Path
        Output file.
    options : DrawingOptions
        Sheet, face size (``pitch``), tabs, marks and styles.
    title : str
        The shape's name for the title line.

    Returns
    -------
    DrawingResult
    """
    from voxfab.drawing import FORMATS
    from voxfab.errors import UnknownFormatError

    from ._writers import write

    if Path(path).suffix.lower() not in FORMATS:
        raise UnknownFormatError(f"{path}: unknown drawing format {Path(path).suffix or '(none)'!r}; "
                                 f"expected one of {', '.join(FORMATS)}")
    grid, colours = shape_colours(shape)
    drawing = _draw_any(grid, nets, options, title, colours=colours)
    return _result(drawing, write(drawing, Path(path), options))


def save_drawing(drawing: NetDrawing, path: str | Path, options: DrawingOptions) -> list[str]:
    """Write a drawn net (:func:`draw_net`, :func:`draw_pieces`) to ``path``; return the paths written.

    The extension picks the format, as in :func:`write_net_drawing`, which draws and
    writes in one call; this one writes a drawing made once in several formats.
    """
    from ._writers import write

    return write(drawing, Path(path), options)


def _draw_any(grid: Any, nets: Net | list[Net], options: DrawingOptions, title: str,
              placement: Any = None, colours: Any = None) -> NetDrawing:
    from voxfab.unfold import Net

    from ._drawing import draw_net as _draw_one
    from ._drawing import draw_pieces as _draw_many

    pieces = [nets] if isinstance(nets, Net) else list(nets)
    if placement is not None:
        from ._drawing import placement_for
        from ._placement import Placement

        where = placement if isinstance(placement, Placement) else Placement.from_dict(placement)
        # A one-piece net where the drawing puts it by itself is drawn as the CLI draws it, byte for byte.
        if not (len(pieces) == 1 and where == placement_for(grid, pieces, options)):
            return _draw_many(grid, pieces, options=options, name=title, placement=where, colours=colours)
    if len(pieces) == 1:
        return _draw_one(grid, pieces[0], options=options, name=title, colours=colours)
    return _draw_many(grid, pieces, options=options, name=title, colours=colours)


def _result(drawing: NetDrawing, files: list[str]) -> DrawingResult:
    return DrawingResult(files, drawing.report(), drawing.warnings(), drawing.pitch,
                         [sheet.fill for sheet in drawing.sheets], len(drawing.marked_seams))


_PURPOSES = {
    "svg": "net for laser cutters and Inkscape (mm): cut red, mountain folds magenta dashed, valley folds "
           "green dash-dot, seam labels black; one layer per line type",
    "dxf": "net for CAD and laser shops (mm): layers CUT, MOUNTAIN, VALLEY, GRID, LABEL, straight lines only",
    "pdf": "net to print at 100 % (no fit to page) on card and cut by hand: cut along the red lines, "
           "fold magenta dashed lines away from you and green dash-dot lines towards you, glue each tab under "
           "the other edge of the same label (each label stands on its edge)",
    "png": "preview of the net sheets to look at: visible lines, shaded tabs, a legend",
}


#: What a coloured net's print files are for (DXF stays lines).
_COLOURED = {
    "svg": "coloured net (mm): each face in its voxel's colour with a bleed past the cut, folds dashed "
           "(mountain) and dash-dot (valley) and seam labels in black or white, whichever reads on the face",
    "pdf": "coloured net to print at 100 % (no fit to page) and cut along the outline: each face in its voxel's "
           "colour, running a little past the cut; glue each tinted tab under the face of its colour",
    "png": "preview of the coloured net sheets",
}
_CUT_PURPOSE = ("the cut lines alone, for the print-then-cut cutter: in register with the print, the same "
                "registration marks at the same place")


def fabricate_net(shape: VoxelShape, net: NetOptions, drawing: DrawingOptions, outdir: str | Path, *, name: str,
                  seed: int, constraints: Any = None, chosen: Any = None, placement: Any = None) -> Artefact:
    """The paper net of ``shape``: ``net.json`` and its drawings, fitted to the sheet.

    Parameters
    ----------
    shape : VoxelShape
    net : NetOptions
        Search options and the drawing formats (``face_size`` is already in
        ``drawing.pitch``).
    drawing : DrawingOptions
        Sheet, face size, tabs, marks and styles.
    outdir : str or Path
        Folder the files go to.
    name, seed : str, int
        Shape name (in the title) and seed of the net.
    constraints : voxfab.unfold.EdgeConstraints, optional
        Edges to cut or keep folded.
    chosen : Net or list of Net, optional
        A net chosen already (the studio's gallery pick): drawn as it is, after the
        same validation, instead of searching one.
    placement : Placement or its JSON form, optional
        Where the pieces of ``chosen`` go on the sheets (the studio's layout),
        checked for overlap and the margin before the drawings are written.

    Returns
    -------
    Artefact
        ``net.json`` (``net.piece-N.json`` per piece) and the drawings, the
        warnings (net split, seams without tabs), a report
        with the face size and the fill of every sheet, and the net it wrote
        as ``gives["net"]``: a tuple of its pieces (one for a one-piece net).
    """
    from voxfab._shared.atomic import write_text
    from voxfab.fabricate._outputs import Artefact

    from ._pipeline import search_nets, validate_net

    if chosen is None:
        found = search_nets(shape.grid, dataclasses.replace(net, count=1), drawing, seed=seed,
                            constraints=constraints)
        nets, fitted, notes = found.nets[0], found.options, list(found.notes)
    else:
        nets = list(chosen) if isinstance(chosen, (list, tuple)) else [chosen]
        fitted, notes = drawing, []
    grid, colours = shape_colours(shape, nets[0].filled)
    validate_net(shape.grid, nets, constraints=constraints)
    outdir = Path(outdir)
    files = []
    for i, piece in enumerate(nets):
        json_name = "net.json" if len(nets) == 1 else f"net.piece-{i + 1}.json"
        write_text(outdir / json_name, piece.to_json(colours))
        files.append(OutputFile(json_name, "the net as voxfab-net/1 JSON: each face's voxel, normal, 3D and 2D "
                                           "corners, and the folds"))
    if chosen is not None and not net.formats:
        # The chosen net itself, with nothing to draw: no sheet to fit, no marks to size.
        return Artefact(tuple(files), (), {"faces": sum(n.face_count for n in nets), "pieces": len(nets)},
                        gives={"net": tuple(nets)})
    from ._writers import write

    drawing = _draw_any(grid, nets, fitted, name, placement, colours)
    for f in net.formats:
        written = write(drawing, outdir / f"net.{f}", fitted)
        purpose = _COLOURED.get(f, _PURPOSES[f]) if drawing.coloured else _PURPOSES[f]
        files += [OutputFile(Path(p).relative_to(outdir).as_posix(),
                             _CUT_PURPOSE if ".cut." in Path(p).name else purpose) for p in written
                  if Path(p).relative_to(outdir).as_posix() not in {o.path for o in files}]  # one cut file
    result = _result(drawing, [])
    report = {"face_size_mm": result.face_size, "faces": sum(n.face_count for n in nets), "pieces": len(nets),
              "sheets": len(result.fill),
              "sheet_fill": [round(f, 4) for f in result.fill], "seams_without_tab_room": result.seams_without_tab,
              "notes": notes}
    return Artefact(tuple(files), tuple(result.warnings), report, gives={"net": tuple(nets)})
