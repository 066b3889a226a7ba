"""Net drawing options, declared once: sheet sizes, face size, tabs, marks, perforation and the colour map."""

from __future__ import annotations

import dataclasses
from enum import Enum

from voxfab._shared.options import OptionError, Options, option
from voxfab.drawing import (
    CUTTERS,
    SHEETS,
    Cutter,
    LayerStyle,
    Lines,
    parse_colors,
    parse_sheet,
    sheet_problem,
)
from voxfab.drawing.dxf import dxf_version_option
from voxfab.errors import InvalidShapeError


class Perforate(Enum):
    """Which fold type becomes short through-cuts on the CUT layer."""

    NONE = "none"
    MOUNTAIN = "mountain"
    VALLEY = "valley"


def _colors_problem(value: str) -> str | None:
    try:
        parse_colors(value)
    except InvalidShapeError as exc:
        return str(exc).removeprefix("colors: ")
    return None


@dataclasses.dataclass(frozen=True)
class DrawingOptions(Options):
    """How a net is drawn: sheet, face size, glue tabs, marks and line styles.

    ``pitch`` is the face size in mm (set from ``face_size`` by the front
    ends); ``None`` picks the largest, in 0.1 mm steps, at which the net fits
    one sheet.  Seam labels shrink from ``label_height`` to fit the faces but
    never below ``min_label_height``, and tabs never below ``min_tab_depth``:
    smaller faces are refused with the smallest face size that works, unless
    labels (``numbers``) or tabs are switched off.
    """

    pitch: float | None = option(None, help="face edge (set from face_size)", unit="mm", low=0.0, low_open=True,
                                 high=1000.0, cli=False, recipe=False)
    sheet: str = option("A4", help=f"sheet: {', '.join(SHEETS)}, or WxH in mm for a laser bed",
                        check=sheet_problem, metavar="A4|A3|...|WxH")
    margin: float = option(10.0, help="empty border of the sheet", unit="mm", low=0.0, high=1000.0)
    tab_width: float = option(5.0, help="largest glue tab height", unit="mm", low=0.0, low_open=True, high=100.0)
    tab_angle: float = option(45.0, help="angle of the tab sides to their fold", unit="degrees", low=15.0,
                              high=75.0)
    label_height: float = option(5.0, help="largest height of the seam labels; they shrink to fit the faces",
                                 unit="mm", low=0.0, low_open=True, high=100.0)
    min_label_height: float = option(2.0, help="smallest height of the seam labels: smaller faces are refused "
                                     "with the face size that works", unit="mm", low=0.0, low_open=True,
                                     high=100.0)
    min_tab_depth: float = option(3.0, help="smallest glue tab: smaller faces are refused likewise", unit="mm",
                                  low=0.0, low_open=True, high=100.0)
    title_height: float = option(3.0, help="height of the title line", unit="mm", low=0.0, low_open=True,
                                 high=100.0, cli=False, recipe=False)
    grid_lines: bool = option(False, help="draw coplanar folds as a faint score (the voxel grid as part of the art)")
    perforate: str = option("none", help="cut this fold type as short perforations (a laser scores one side only)",
                            choices=tuple(p.value for p in Perforate))
    perf_cut: float = option(1.5, help="perforation cut length", unit="mm", low=0.0, low_open=True, high=100.0)
    perf_bridge: float = option(1.0, help="perforation bridge length", unit="mm", low=0.0, low_open=True,
                                high=100.0)
    svg_lines: str = option("laser", help="SVG line widths: laser hairlines, or visible lines to look at",
                            choices=tuple(v.value for v in Lines))
    dxf_version: str = dxf_version_option()
    colors: str = option("", help="colour map, e.g. 'cut=#ff0000,mountain=blue:dashed'; layers CUT SCORE "
                         "MOUNTAIN VALLEY GRID LABEL, styles solid dashed dashdot dotted", check=_colors_problem,
                         metavar="LAYER=COLOR[:STYLE],...")
    numbers: bool = option(True, help="draw the seam labels (--no-numbers for faces too small to carry them)")
    tabs: bool = option(True, help="draw glue tabs (--no-tabs: seams are marked for tape)")
    heading: bool = option(True, help="print the title line", cli=False, recipe=False)
    bleed: float = option(1.0, help="coloured nets: the face colours run this far past the cut lines, so a print "
                          "cut a little off shows no white edge", unit="mm", low=0.0, high=10.0)
    cutter: str = option("none", help="print-then-cut files for this cutter: its registration marks on the print, which "
                         "has no cut lines; the cut lines alone in NAME.cut.svg, in register",
                         choices=tuple(c.value for c in Cutter))

    def check(self) -> None:
        """Rules between options: tabs and labels at least their minimum, room inside the margin."""
        if self.tabs and self.tab_width < self.min_tab_depth:
            raise OptionError("tab_width", f"{self.tab_width:g} mm is under the {self.min_tab_depth:g} mm "
                              "smallest tab (min_tab_depth)")
        if self.numbers and self.label_height < self.min_label_height:
            raise OptionError("label_height", f"{self.label_height:g} mm is under the {self.min_label_height:g} "
                              "mm smallest number (min_label_height)")
        w, h = self.sheet_size
        if min(w, h) <= 2 * self.edge + self.title_height + 4:
            raise OptionError("sheet", f"{self.sheet} leaves no room inside a {self.edge:g} mm margin")

    @property
    def edge(self) -> float:
        """The sheet's empty border, mm: the margin, or the room the cutter's registration marks need."""
        marks = CUTTERS.get(Cutter(self.cutter))
        return max(float(self.margin), marks.margin) if marks else float(self.margin)

    @property
    def sheet_size(self) -> tuple[float, float]:
        """Sheet width and height, mm."""
        return parse_sheet(self.sheet)

    @property
    def styles(self) -> dict[str, LayerStyle]:
        """Layer styles after applying ``colors``."""
        return parse_colors(self.colors)
