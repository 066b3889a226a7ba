"""Net drawings: cut outlines, mountain/valley folds, glue tabs and edge numbers as SVG, DXF, PDF and PNG.

A net from :mod:`voxfab.unfold` becomes a sheet that a laser cutter or a home
printer takes as is: one closed cut outline per piece, folds typed as seen from
outside, one non-overlapping glue tab per seam, matching single-stroke numbers
on both edges of every seam, and a title with the shape's name, face size and
seed.  Numbers are at least 2 mm tall and tabs at least 3 mm deep; smaller
faces are refused with the smallest face size that works.  A net that does not
fit its sheet is refused too, naming the largest face size at which it fits and
the smallest sheet that takes it; pieces (``pieces="auto"``) are packed on as
few sheets as possible.

Public API: :func:`find_sheet_nets` (shape → nets that fit the sheet),
:func:`draw_net` and :func:`draw_pieces` (nets → :class:`Drawing`),
:func:`write_drawing`, :func:`add_drawing_arguments` for the ``voxfab net``
command, and :func:`recipe_output` for recipes.  Heavy libraries (shapely,
ezdxf, scipy, rectpack) load only when a drawing is made.
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from voxfab.drawing import LayerStyle, LineStyle, parse_colors

# Light imports only: the recipe loader resolves the hints of recipe_output at runtime.
from voxfab.fabricate._registry import OutputFile
from voxfab.shape import VoxelShape
from voxfab.unfold import Net

from ._options import SHEETS, DrawingOptions, parse_sheet
from ._sheets import SheetFitError

if TYPE_CHECKING:
    from ._drawing import Drawing
    from ._fit import SheetNets

__all__ = [
    "SHEETS",
    "Drawing",
    "DrawingOptions",
    "LayerStyle",
    "LineStyle",
    "DrawingResult",
    "SheetFitError",
    "SheetNets",
    "add_drawing_arguments",
    "draw_net",
    "draw_pieces",
    "find_sheet_nets",
    "drawing_formats",
    "options_from_args",
    "parse_colors",
    "parse_sheet",
    "recipe_output",
    "write_drawing",
    "write_net_drawing",
]

_DEFAULTS = DrawingOptions()


def __getattr__(name: str) -> Any:
    # Keep `import voxfab.fabricate.netdraw` light for the CLI: the drawing code
    # (and shapely behind it) loads on first use.
    if name == "Drawing":
        from ._drawing import Drawing

        return Drawing
    if name == "SheetNets":
        from ._fit import SheetNets

        return SheetNets
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def draw_net(grid: Any, net: Net, *, options: DrawingOptions | None = None, name: str = "") -> Drawing:
    """Lay ``net`` (a net of ``grid``) out on sheets; see :func:`._drawing.draw_net`."""
    from ._drawing import draw_net as _draw

    return _draw(grid, net, options=options, name=name)


def draw_pieces(grid: Any, pieces: list[Net], *, options: DrawingOptions | None = None, name: str = "") -> Drawing:
    """Pack the pieces of a net on as few sheets as possible; see :func:`._drawing.draw_pieces`."""
    from ._drawing import draw_pieces as _draw

    return _draw(grid, pieces, options=options, name=name)


def find_sheet_nets(grid: Any, options: DrawingOptions, *, rng: int, pieces: str = "one", count: int = 1,
                    **search: Any) -> SheetNets:
    """Nets of ``grid`` that fit the sheet of ``options``; see :func:`._fit.find_sheet_nets`."""
    from ._fit import find_sheet_nets as _find

    return _find(grid, options, rng=rng, pieces=pieces, count=count, **search)


def drawing_formats() -> list[str]:
    """File extensions :func:`write_drawing` understands."""
    from ._writers import drawing_formats as _formats

    return _formats()


def add_drawing_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the drawing options (sheet, tabs, styles) to a ``voxfab net`` parser.

    The pitch, output paths, seed and search options belong to the command itself.
    """
    g = parser.add_argument_group("drawings (-o with .svg, .dxf, .pdf or .png)")
    g.add_argument("--sheet", default=_DEFAULTS.sheet, metavar="A4|A3|Letter|...|WxH",
                   help=f"sheet size ({', '.join(SHEETS)}), or W x H in mm for a laser bed (default A4)")
    g.add_argument("--margin", type=float, default=_DEFAULTS.margin, metavar="MM",
                   help=f"empty border of the sheet in mm (default {_DEFAULTS.margin:g})")
    g.add_argument("--tab-width", type=float, default=_DEFAULTS.tab_width, metavar="MM",
                   help=f"glue tab height in mm (default {_DEFAULTS.tab_width:g})")
    g.add_argument("--tab-angle", type=float, default=_DEFAULTS.tab_angle, metavar="DEG",
                   help=f"angle of the tab sides in degrees, 15 to 75 (default {_DEFAULTS.tab_angle:g})")
    g.add_argument("--label-height", type=float, default=_DEFAULTS.label_height, metavar="MM",
                   help="largest height of the edge numbers in mm; they shrink to fit small faces "
                   f"(default {_DEFAULTS.label_height:g})")
    g.add_argument("--min-label-height", type=float, default=_DEFAULTS.min_label_height, metavar="MM",
                   help="smallest height of the edge numbers in mm: smaller faces are refused with the face "
                   f"size that works (default {_DEFAULTS.min_label_height:g})")
    g.add_argument("--min-tab-depth", type=float, default=_DEFAULTS.min_tab_depth, metavar="MM",
                   help=f"smallest glue tab in mm, refused likewise (default {_DEFAULTS.min_tab_depth:g})")
    g.add_argument("--no-numbers", dest="numbers", action="store_false",
                   help="draw no edge numbers (for faces too small to carry them)")
    g.add_argument("--no-tabs", dest="tabs", action="store_false",
                   help="draw no glue tabs: seams are marked for tape")
    g.add_argument("--svg-lines", choices=["laser", "preview"], default=_DEFAULTS.svg_lines,
                   help="SVG line widths: laser hairlines (default) or visible lines to look at in a browser")
    g.add_argument("--dxf-version", choices=["R12", "R2000"], default=_DEFAULTS.dxf_version,
                   help="DXF version: R12 (default, widest laser support) or R2000 (with $INSUNITS=mm)")
    g.add_argument("--grid-lines", action="store_true",
                   help="draw coplanar folds as a faint score (the voxel grid as part of the art)")
    g.add_argument("--perforate", choices=["none", "mountain", "valley"], default=_DEFAULTS.perforate,
                   help="cut this fold type as short perforations, since a laser scores one side only")
    g.add_argument("--perf-cut", type=float, default=_DEFAULTS.perf_cut, metavar="MM",
                   help=f"perforation cut length in mm (default {_DEFAULTS.perf_cut:g})")
    g.add_argument("--perf-bridge", type=float, default=_DEFAULTS.perf_bridge, metavar="MM",
                   help=f"perforation bridge length in mm (default {_DEFAULTS.perf_bridge:g})")
    g.add_argument("--colors", default="", metavar="LAYER=COLOR[:STYLE],...",
                   help="change the colour map, e.g. 'cut=#ff0000,mountain=blue:dashed,valley=green:dashdot'; "
                   "layers CUT SCORE MOUNTAIN VALLEY GRID LABEL, styles solid dashed dashdot dotted")


def options_from_args(args: argparse.Namespace) -> DrawingOptions:
    """DrawingOptions from parsed arguments (missing ones keep their defaults)."""
    values = {
        f.name: getattr(args, f.name)
        for f in dataclasses.fields(DrawingOptions)
        if getattr(args, f.name, None) is not None
    }
    return DrawingOptions(**values)


@dataclasses.dataclass(frozen=True)
class DrawingResult:
    """What writing a net drawing did.

    Attributes
    ----------
    files : list of str
        Paths written.
    report : list of str
        Face size, sheets and their fill, tabs, numbers and folds.
    warnings : list of str
        The lines a maker must read before making it (a net split into pieces,
        numbers shrunk, seams without tabs); also the last lines of ``report``.
    face_size : float
        Face edge, mm.
    fill : list of float
        Share of each sheet covered by paper, 0 to 1.
    """

    files: list[str]
    report: list[str]
    warnings: list[str]
    face_size: float
    fill: list[float]


def write_net_drawing(grid: Any, nets: Net | list[Net], path: str | Path, options: DrawingOptions, *,
                      title: str = "") -> DrawingResult:
    """Draw a net (or the pieces of one, packed) of ``grid`` and write it to ``path``.

    The extension picks the format: ``.svg`` and ``.dxf`` are laser files (one
    per sheet, named ``NAME.sheet-N.ext`` when there are several), ``.pdf`` and
    ``.png`` are for people (visible lines, shaded tabs, a legend).

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The shape the net unfolds.
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

    from ._drawing import draw_net as _draw_one
    from ._drawing import draw_pieces as _draw_many
    from ._writers import write

    if Path(path).suffix.lower() not in FORMATS:
        raise UnknownFormatError(f"{path}: unknown drawing format {Path(path).suffix or '(none)'!r}; "
                                 f"expected one of {', '.join(FORMATS)}")
    pieces = [nets] if isinstance(nets, Net) else list(nets)
    if len(pieces) == 1:
        drawing = _draw_one(grid, pieces[0], options=options, name=title)
    else:
        drawing = _draw_many(grid, pieces, options=options, name=title)
    files = write(drawing, Path(path), options)
    return DrawingResult(files, drawing.report(), drawing.warnings(), drawing.pitch,
                         [sheet.fill for sheet in drawing.sheets])


def write_drawing(shape: VoxelShape, net: Net | list[Net], path: str | Path,
                  options: DrawingOptions | argparse.Namespace, *, title: str = "") -> list[str]:
    """Draw ``net`` of ``shape`` and write it to ``path``; the report lines and the files written.

    ``options`` may be parsed arguments of :func:`add_drawing_arguments` (with
    ``pitch``, the face size).  See :func:`write_net_drawing`.
    """
    opts = options if isinstance(options, DrawingOptions) else options_from_args(options)
    result = write_net_drawing(shape.grid, net, path, opts, title=title)
    return result.report + [f"wrote {p}" for p in result.files]


_PURPOSES = {
    "svg": "net for laser cutters and Inkscape (mm): cut red, mountain folds blue dashed, valley folds "
           "green dash-dot, numbers black; one layer per line type",
    "dxf": "net for CAD and laser shops (mm): layers CUT, MOUNTAIN, VALLEY, GRID, LABEL, straight lines only",
    "pdf": "net to print at 100 % (no fit to page) on card and cut by hand: cut along the red lines, "
           "fold blue dashed lines away from you and green dash-dot lines towards you, glue tab N under edge N",
    "png": "preview of the net sheets to look at: visible lines, shaded tabs, a legend",
}


def recipe_output(
    shape: VoxelShape,
    outdir: Path,
    *,
    name: str,
    seed: int,
    formats: list[str] | None = None,
    sheet: str = "A4",
    pitch: float | None = None,
    fit: bool = True,
    pieces: Literal["one", "auto"] = "one",
    margin: float = 10.0,
    tab_width: float = 5.0,
    tab_angle: float = 45.0,
    label_height: float = 5.0,
    numbers: bool = True,
    grid_lines: bool = False,
    perforate: Literal["none", "mountain", "valley"] = "none",
    dxf_version: Literal["R12", "R2000"] = "R12",
    colors: str = "",
    fill: bool = False,
    timeout: float = 60.0,
) -> list[OutputFile]:
    """The recipe output ``net``: a paper net as JSON and as drawings.

    Parameters
    ----------
    shape : VoxelShape
        The recipe's shape.
    outdir : Path
        Folder the files go to.
    name, seed : str, int
        Recipe name (in the title) and seed of the net.
    formats : list of str, optional
        Drawing formats among ``svg``, ``dxf``, ``pdf``, ``png`` (default ``svg``,
        ``dxf``, ``pdf``).
    sheet : str
        A sheet of :data:`SHEETS` or ``WxH`` in mm.
    pitch : float, optional
        Face size in mm; by default the largest that puts a compact net on one sheet.
    fit : bool
        Kept for old recipes: nets are always searched to fit the sheet.
    pieces : {"one", "auto"}
        ``auto``: when no one-piece net fits, the fewest pieces packed on sheets.
    margin, tab_width, tab_angle, label_height, numbers, grid_lines, perforate, dxf_version, colors
        See :class:`DrawingOptions`.
    fill : bool
        Unfold the outer surface only, as if enclosed cavities were filled: a paper
        model is hollow anyway, and a cavity's own surface cannot join the net.
    timeout : float
        Time budget of the net search, seconds.

    Returns
    -------
    list of OutputFile
        ``net.json`` (one per piece) and the drawings.
    """
    from voxfab import unfold
    from voxfab._shared.atomic import write_text
    from voxfab.errors import RecipeError
    from voxfab.shape import fill_cavities

    del fit
    chosen = ["svg", "dxf", "pdf"] if formats is None else list(formats)
    for f in chosen:
        if f not in _PURPOSES:
            raise RecipeError(f"net.formats: unknown format {f!r}; expected some of {', '.join(_PURPOSES)}")
    options = DrawingOptions(
        pitch=pitch, sheet=sheet, margin=margin, tab_width=tab_width, tab_angle=tab_angle,
        label_height=label_height, numbers=numbers, grid_lines=grid_lines, perforate=perforate,
        dxf_version=dxf_version, colors=colors,
    )
    found = find_sheet_nets(shape.grid, options, rng=seed, pieces=pieces, fill=fill, timeout=timeout)
    nets = found.nets[0]
    grid = fill_cavities(shape.grid) if nets[0].filled else shape.grid
    unfold.validate(grid, nets if len(nets) > 1 else nets[0])
    outdir = Path(outdir)
    files = []
    for i, net in enumerate(nets):
        json_name = "net.json" if len(nets) == 1 else f"net.piece-{i + 1}.json"
        write_text(outdir / json_name, net.to_json())
        files.append(OutputFile(json_name, "the net as voxfab-net/1 JSON: each face's voxel, normal, 3D and 2D "
                                           "corners, and the folds"))
    for f in chosen:
        result = write_net_drawing(grid, nets, outdir / f"net.{f}", found.options, title=name)
        for p in result.files:
            files.append(OutputFile(Path(p).relative_to(outdir).as_posix(), _PURPOSES[f]))
    return files
