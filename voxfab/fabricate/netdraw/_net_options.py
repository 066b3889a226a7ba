"""The search options of a paper net, declared once (CLI flags, recipe keys, checks, README table), and what
a search for a sheet gives back (:class:`SheetNets`).

The drawing options (sheet, tabs, styles) are :class:`DrawingOptions`.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

from voxfab._shared.options import Options, option

if TYPE_CHECKING:
    from voxfab.unfold import Net

    from ._options import DrawingOptions

#: Longest search budget accepted, seconds.
MAX_TIMEOUT = 3600.0
#: Most nets one command writes.
MAX_COUNT = 1000


@dataclasses.dataclass(frozen=True)
class NetOptions(Options):
    """How a net is searched for, and at what scale it is drawn.

    ``face_size`` is the paper scale, explicit and separate from the shape's
    pitch (mm per voxel of the printed object): paper needs larger faces than a
    print.  ``None`` takes the shape's pitch; a shape that has no pitch gets the
    largest face size at which a one-piece net fits the sheet.
    """

    face_size: float | None = option(None, help="edge of one paper face (default: the shape's pitch)",
                                     unit="mm", low=0.0, low_open=True, high=1000.0)
    strategy: str = option("default", help="search strategy: ruin-and-recreate with tab room, paper, or exact "
                           "(a complete search in --box or --min-box: a net, or a proof that none fits; with "
                           "neither, a net in a box that holds any, the same on every run; needs ortools)", choices=("default", "paper", "exact"))
    timeout: float = option(60.0, help="search budget per net", unit="s", low=0.0, low_open=True,
                            high=MAX_TIMEOUT)
    count: int = option(1, help="write N distinct nets as NAME-1.ext ... NAME-N.ext", low=1, high=MAX_COUNT,
                        recipe=False, metavar="N")
    budget: float = option(60.0, help="search budget for all the nets of --count together", unit="s", low=0.0,
                           low_open=True, high=MAX_TIMEOUT, recipe=False)
    pieces: str = option("one", help="auto: when no one-piece net fits the sheet, compact pieces (whole flat "
                         "patches of the surface), packed on as few sheets as possible", choices=("one", "auto"))
    fill: bool = option(False, help="unfold the outer surface only, as if enclosed cavities were filled")
    compact: bool = option(False, help="prefer a small bounding box (slower)")
    min_box: bool = option(False, help="strategy exact: the net of least bounding-box area, every smaller "
                           "area proved to have none", recipe=False)
    zipper: bool = option(False, help="strategy exact: the cut edges form one path (an unzipping), or a proof "
                          "that no such net fits", recipe=False)
    fit: bool = option(True, help="kept for old recipes: drawn nets always fit their sheet", cli=False)
    formats: tuple[str, ...] = option(("svg", "dxf", "pdf"), help="drawings written beside net.json (png: a "
                                      "preview)", choices=("svg", "dxf", "pdf", "png"), cli=False)


@dataclasses.dataclass(frozen=True, eq=False)
class SheetNets:
    """Nets found for a sheet.

    Attributes
    ----------
    nets : list of list of Net
        Each result as its pieces (one Net for a one-piece net).
    options : DrawingOptions
        The drawing options with the face size settled.
    notes : list of str
        Report lines (how many distinct nets were found, the face size chosen).
    best_extent : (int, int) or None
        When no one-piece net fits at the face size asked for (``show_unfit``): the extent of the
        net measured to fit the sheet at the largest face size, for the words of each net shown.
    """

    nets: list[list[Net]]
    options: DrawingOptions
    notes: list[str]
    best_extent: tuple[int, int] | None = None
