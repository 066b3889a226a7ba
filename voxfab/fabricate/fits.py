"""Does a one-piece net of this shape fit this sheet?  An exact answer: yes with a net, no (proved), or undecided.

The sheet and the face size give the box of faces a drawn net may take (the
drawing's own rule, :func:`voxfab.fabricate.netdraw._sheets.sheet_cells`: the
sheet less its margins and a glue tab all round); the exact strategy then finds
a net in that box or proves that none exists (:mod:`voxfab.unfold._exact`).
"""

from __future__ import annotations

import dataclasses
from typing import Any

from voxfab.unfold import Net

__all__ = ["FITS_ANSWERS", "SheetFit", "fits_sheet"]

#: The three answers.
FITS_ANSWERS = ("yes", "no", "undecided")
#: Longest exact search accepted, seconds.
MAX_FITS_SECONDS = 600.0


@dataclasses.dataclass(frozen=True, eq=False)
class SheetFit:
    """The answer to "does a one-piece net fit this sheet?".

    Attributes
    ----------
    answer : str
        ``yes`` (``net`` is one), ``no`` (proved: no one-piece net fits) or
        ``undecided`` (the time ran out first).
    box : (int, int)
        Faces across and down the sheet at this face size.
    faces : int
        Faces of the surface (the outer one: cavities are filled).
    net : Net or None
        The net that fits, turned or not.
    message : str
        The answer in one line.
    """

    answer: str
    box: tuple[int, int]
    faces: int
    net: Net | None
    message: str


def fits_sheet(grid: Any, sheet: str = "A4", face_size: float = 10.0, *, timeout: float = 30.0,
               drawing: Any = None) -> SheetFit:
    """Whether a one-piece net of ``grid`` fits ``sheet`` at ``face_size`` mm per face, decided exactly.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        One piece of face-connected voxels; enclosed cavities are filled.
    sheet : str
        A sheet name (``A4``, ``Letter``, ...) or ``WxH`` in mm.
    face_size : float
        Edge of one paper face in mm.
    timeout : float
        Seconds for the exact search.
    drawing : DrawingOptions, optional
        The drawing whose margin and tabs take room on the sheet (default: the default drawing's).

    Returns
    -------
    SheetFit

    Raises
    ------
    InvalidShapeError
        A bad sheet, face size or timeout, or a shape in several pieces.
    """
    import math

    from voxfab._shared.validate import as_grid
    from voxfab.errors import InvalidShapeError, NoNetExistsError
    from voxfab.shape import fill_cavities, surface_graph
    from voxfab.unfold import Undecided, unfold

    from .netdraw import DrawingOptions
    from .netdraw._sheets import sheet_cells

    def number(value: Any) -> float:
        try:
            return float(value)
        except (TypeError, ValueError):
            return math.nan

    size = number(face_size)
    if not 0 < size <= 1000.0:
        raise InvalidShapeError(f"face_size: expected a number of mm over 0 and at most 1000, got {str(face_size)[:40]}")
    seconds = number(timeout)
    if not 0 < seconds <= MAX_FITS_SECONDS:
        raise InvalidShapeError(f"timeout: expected seconds over 0 and at most {MAX_FITS_SECONDS:g}, "
                                f"got {str(timeout)[:40]}")
    # the sheet checked with the drawing's own words; its margin and tabs take their room
    options = (drawing if drawing is not None else DrawingOptions()).replace(sheet=sheet, pitch=size)
    box = sheet_cells(options, size)
    where = f"{sheet} at {size:g} mm faces ({box[0]}x{box[1]} faces)"
    g = as_grid(grid)
    faces = surface_graph(fill_cavities(g)).face_count if g.any() else 0
    if min(box) < 1:
        return SheetFit("no", box, faces, None, f"no: a face of {size:g} mm does not fit {sheet} with its "
                                                 "margins and tabs")
    try:
        net = unfold(g, rng=0, strategy="exact", fit=box, fill=True, timeout=seconds)
    except NoNetExistsError:
        return SheetFit("no", box, faces, None, f"no: no one-piece net of the {faces}-face surface fits {where} "
                                                 "(proved)")
    except Undecided:
        return SheetFit("undecided", box, faces, None, f"undecided: the exact search found no one-piece net "
                        f"that fits {where}, nor proved that none does, within {seconds:g} s")
    x0, y0, x1, y1 = net.bounds()  # type: ignore[union-attr]
    return SheetFit("yes", box, faces, net,  # type: ignore[arg-type]
                    f"yes: a one-piece net of {x1 - x0}x{y1 - y0} faces fits {where}")
