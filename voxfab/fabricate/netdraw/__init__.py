"""Net drawings: cut outlines, mountain/valley folds, glue tabs and edge numbers as SVG, DXF and PDF.

A net from :mod:`voxfab.unfold` becomes sheets that a laser cutter or a home
printer takes as is: one closed cut outline per piece, folds typed as seen from
outside, one non-overlapping glue tab per seam, matching single-stroke numbers
on both edges of every seam, and a title with the shape's name, pitch and seed.

Public API: :func:`draw_net` (net → :class:`Drawing`), :func:`write_drawing`
and :func:`add_drawing_arguments` for the ``voxfab net`` command, and
:func:`recipe_output` for recipes.  Heavy libraries (shapely, ezdxf, scipy)
load only when a drawing is made.
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from voxfab.drawing import LayerStyle, LineStyle, parse_colors

# Light imports only: the recipe loader resolves the hints of recipe_output at runtime.
from voxfab.fabricate._outputs import OutputFile
from voxfab.shape import VoxelShape
from voxfab.unfold import Net

from ._net_options import NetOptions
from ._options import SHEETS, DrawingOptions, parse_sheet

if TYPE_CHECKING:
    from ._drawing import Drawing

__all__ = [
    "SHEETS",
    "Drawing",
    "DrawingOptions",
    "LayerStyle",
    "LineStyle",
    "NetOptions",
    "add_drawing_arguments",
    "draw_net",
    "drawing_formats",
    "options_from_args",
    "parse_colors",
    "parse_sheet",
    "recipe_output",
    "write_drawing",
]

_DEFAULTS = DrawingOptions()


def __getattr__(name: str) -> Any:
    # Keep `import voxfab.fabricate.netdraw` light for the CLI: the drawing code
    # (and shapely behind it) loads on first use.
    if name == "Drawing":
        from ._drawing import Drawing

        return Drawing
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def draw_net(grid: Any, net: Net, *, options: DrawingOptions | None = None, name: str = "") -> Drawing:
    """Lay ``net`` (a net of ``grid``) out on sheets; see :func:`._drawing.draw_net`."""
    from ._drawing import draw_net as _draw

    return _draw(grid, net, options=options, name=name)


def drawing_formats() -> list[str]:
    """File extensions :func:`write_drawing` understands."""
    from ._writers import drawing_formats as _formats

    return _formats()


def add_drawing_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the drawing options (sheet, tabs, styles) to a ``voxfab net`` parser.

    The pitch, output paths, seed and search options belong to the command itself.
    """
    g = parser.add_argument_group("drawings (-o with .svg, .dxf or .pdf)")
    g.add_argument("--sheet", default=_DEFAULTS.sheet, metavar="A4|A3|Letter|WxH",
                   help="sheet size, or W x H in mm for a laser bed (default A4)")
    g.add_argument("--margin", type=float, default=_DEFAULTS.margin, metavar="MM",
                   help=f"empty border of the sheet in mm (default {_DEFAULTS.margin:g})")
    g.add_argument("--tab-width", type=float, default=_DEFAULTS.tab_width, metavar="MM",
                   help=f"glue tab height in mm (default {_DEFAULTS.tab_width:g})")
    g.add_argument("--tab-angle", type=float, default=_DEFAULTS.tab_angle, metavar="DEG",
                   help=f"angle of the tab sides in degrees, 15 to 75 (default {_DEFAULTS.tab_angle:g})")
    g.add_argument("--label-height", type=float, default=_DEFAULTS.label_height, metavar="MM",
                   help="largest height of the edge numbers in mm; they shrink to fit small faces "
                   f"(default {_DEFAULTS.label_height:g})")
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
                   "layers CUT MOUNTAIN VALLEY GRID LABEL, styles solid dashed dashdot dotted")


def options_from_args(args: argparse.Namespace) -> DrawingOptions:
    """DrawingOptions from parsed arguments (missing ones keep their defaults)."""
    values = {
        f.name: getattr(args, f.name)
        for f in dataclasses.fields(DrawingOptions)
        if getattr(args, f.name, None) is not None
    }
    return DrawingOptions(**values)


def write_drawing(shape: VoxelShape, net: Net, path: str | Path, args: argparse.Namespace, *,
                  title: str = "") -> list[str]:
    """Draw ``net`` of ``shape`` and write it to ``path`` (.svg, .dxf or .pdf).

    Parameters
    ----------
    shape : VoxelShape
        The shape the net unfolds.
    net : Net
        Its net.
    path : str or Path
        Output file; a drawing over several sheets writes ``name-1.svg``,
        ``name-2.svg``, ... (a PDF gets one page per sheet instead).
    args : argparse.Namespace
        Parsed arguments of :func:`add_drawing_arguments`, plus ``pitch`` (mm,
        ``None`` for automatic).
    title : str
        The shape's name for the title line.

    Returns
    -------
    list of str
        Report lines: fitting, tabs, marks, and the files written.
    """
    from ._drawing import draw_net as _draw
    from ._writers import write

    options = options_from_args(args)
    drawing = _draw(shape.grid, net, options=options, name=title)
    written = write(drawing, Path(path), options)
    return drawing.report() + [f"wrote {p}" for p in written]


_PURPOSES = {
    "svg": "net for laser cutters and Inkscape (mm): cut red, mountain folds blue dashed, valley folds "
           "green dash-dot, numbers black; one layer per line type",
    "dxf": "net for CAD and laser shops (mm): layers CUT, MOUNTAIN, VALLEY, GRID, LABEL, straight lines only",
    "pdf": "net to print at 100 % (no fit to page) on card and cut by hand: cut along the red lines, "
           "fold blue dashed lines away from you and green dash-dot lines towards you, glue tab N under edge N",
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
    fit: bool = False,
    margin: float = 10.0,
    tab_width: float = 5.0,
    tab_angle: float = 45.0,
    label_height: float = 5.0,
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
        Drawing formats among ``svg``, ``dxf``, ``pdf`` (default all three).
    sheet : str
        ``A4``, ``A3``, ``Letter`` or ``WxH`` in mm.
    pitch : float, optional
        Face size in mm; by default the largest that puts the net on one sheet.
    fit : bool
        Ask the net engine for a net that fits the sheet at ``pitch`` (needs ``pitch``).
    margin, tab_width, tab_angle, label_height, grid_lines, perforate, dxf_version, colors
        See :class:`DrawingOptions`.
    fill : bool
        Unfold the outer surface only, as if enclosed cavities were filled: a paper
        model is hollow anyway, and a cavity's own surface cannot join the net.
    timeout : float
        Time budget of the net search, seconds.

    Returns
    -------
    list of OutputFile
        ``net.json`` and the drawings.
    """
    from voxfab import unfold
    from voxfab._shared.atomic import write_text
    from voxfab.errors import RecipeError
    from voxfab.shape import fill_cavities

    from ._drawing import draw_net as _draw
    from ._sheets import drawable_area
    from ._writers import write

    chosen = ["svg", "dxf", "pdf"] if formats is None else list(formats)
    for f in chosen:
        if f not in _PURPOSES:
            raise RecipeError(f"net.formats: unknown format {f!r}; expected some of svg, dxf, pdf")
    options = DrawingOptions(
        pitch=pitch, sheet=sheet, margin=margin, tab_width=tab_width, tab_angle=tab_angle,
        label_height=label_height, grid_lines=grid_lines, perforate=perforate, dxf_version=dxf_version,
        colors=colors,
    )
    search: dict[str, Any] = {"rng": seed, "timeout": timeout}
    if fit:
        if pitch is None:
            raise RecipeError("net.fit: needs net.pitch (mm per face) to know how many faces fit the sheet")
        x0, y0, x1, y1 = drawable_area(options)
        pad = 2 * options.tab_width
        search["fit"] = (int((x1 - x0 - pad) // pitch), int((y1 - y0 - pad) // pitch))
    net = unfold.unfold(shape.grid, fill=fill, **search)
    grid = fill_cavities(shape.grid) if net.filled else shape.grid
    unfold.validate(grid, net)
    outdir = Path(outdir)
    write_text(outdir / "net.json", net.to_json())
    files = [OutputFile("net.json", "the net as voxfab-net/1 JSON: each face's voxel, normal, 3D and 2D "
                                    "corners, and the folds")]
    drawing = _draw(grid, net, options=options, name=name)
    for f in chosen:
        for p in write(drawing, outdir / f"net.{f}", options):
            files.append(OutputFile(Path(p).relative_to(outdir).as_posix(), _PURPOSES[f]))
    return files
