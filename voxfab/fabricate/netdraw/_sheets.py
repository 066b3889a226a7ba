"""Fitting a net on a sheet: automatic face size, a quarter turn, pieces packed on sheets.

A net goes on one sheet, turned a quarter turn when that fits better; when it
does not fit, :class:`SheetFitError` says the largest face size at which it
fits this sheet and the smallest standard sheet that takes it at this face
size.  Several pieces (``--pieces auto``) are packed cell by cell, turned by
quarter turns, on as few sheets as possible.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError, UnfoldError

from ._legible import tab_depth
from ._options import SHEETS, DrawingOptions


class SheetFitError(UnfoldError):
    """No net found fits the sheet at the face size asked for.

    Attributes
    ----------
    extent : (int, int)
        Bounding box in faces of the most compact net found.
    largest_face_size : float
        Largest face size (mm, 0.1 mm steps) at which that net fits the sheet.
    smallest_sheet : str or None
        Smallest sheet of :data:`SHEETS` that takes it at the face size asked for.
    """

    def __init__(self, message: str, *, extent: tuple[int, int], largest_face_size: float,
                 smallest_sheet: str | None) -> None:
        super().__init__(message)
        self.extent = extent
        self.largest_face_size = largest_face_size
        self.smallest_sheet = smallest_sheet

    @property
    def ways_out(self) -> list[dict[str, object]]:
        """The choices that would work, in plain words: ``[{"label": ..., "options": {NAME: VALUE}}]``."""
        return ways_out(self.largest_face_size, self.smallest_sheet)


def ways_out(largest: float, sheet: str | None) -> list[dict[str, object]]:
    """Ways out of a net too large for its sheet: pieces, the smallest sheet that takes it, smaller faces."""
    out: list[dict[str, object]] = [{"label": "split it into pieces", "options": {"pieces": "auto"}}]
    if sheet:
        out.append({"label": f"use a larger sheet ({sheet})", "options": {"sheet": sheet}})
    if largest > 0:
        out.append({"label": f"make the faces {largest:g} mm", "options": {"face_size": largest}})
    return out


@dataclasses.dataclass(frozen=True, eq=False)
class SheetPlan:
    """Where every face goes.

    Attributes
    ----------
    pitch : float
        Face edge length, mm.
    rotated : bool
        The net (a single piece) is turned a quarter turn counter-clockwise to fit better.
    corners2d : (F, 4, 2) int ndarray
        Face corners in cells: sheet ``s`` holds cells ``origin[s] / pitch`` onwards,
        and no two sheets share a cell, so faces of different sheets never touch.
    face_sheet : (F,) int ndarray
        Sheet index of each face.
    origin : (S, 2) float ndarray
        Position in mm of cell (0, 0) on each sheet.
    area : tuple of 4 floats
        ``(x0, y0, x1, y1)`` drawable rectangle of every sheet, mm.
    size : tuple of 2 floats
        Sheet width and height, mm.
    """

    pitch: float
    rotated: bool
    corners2d: npt.NDArray[np.int64]
    face_sheet: npt.NDArray[np.int64]
    origin: npt.NDArray[np.float64]
    area: tuple[float, float, float, float]
    size: tuple[float, float]

    @property
    def count(self) -> int:
        """Number of sheets."""
        return int(self.origin.shape[0])

    def face_positions(self) -> npt.NDArray[np.float64]:
        """``(F, 4, 2)`` face corners in mm on their own sheet."""
        return self.origin[self.face_sheet][:, None, :] + self.corners2d * self.pitch


def drawable_area(options: DrawingOptions, size: tuple[float, float] | None = None) -> tuple[float, float, float, float]:
    """``(x0, y0, x1, y1)`` of the sheet inside the margin, above the title band, mm."""
    w, h = options.sheet_size if size is None else size
    m = float(options.margin)
    band = options.title_height + 2.0 if options.heading else 0.0
    return (m, m + band, w - m, h - m)


def _room(options: DrawingOptions, pitch: float, size: tuple[float, float] | None = None) -> tuple[float, float]:
    """Width and height in mm that faces may take: the drawable area less a tab all round."""
    x0, y0, x1, y1 = drawable_area(options, size)
    pad = tab_depth(options, pitch)
    return x1 - x0 - 2 * pad, y1 - y0 - 2 * pad


def sheet_cells(options: DrawingOptions, pitch: float, size: tuple[float, float] | None = None) -> tuple[int, int]:
    """Faces across and down a sheet at face size ``pitch`` (the ``fit`` of the net search)."""
    w, h = _room(options, pitch, size)
    return max(int(math.floor(w / pitch + 1e-9)), 0), max(int(math.floor(h / pitch + 1e-9)), 0)


def fits(extent: tuple[int, int], options: DrawingOptions, pitch: float,
         size: tuple[float, float] | None = None) -> bool | None:
    """Whether a net of ``extent`` faces fits the sheet: False as is, True turned, None not at all."""
    cw, ch = sheet_cells(options, pitch, size)
    ex, ey = extent
    if ex <= cw and ey <= ch:
        return False
    if ey <= cw and ex <= ch:
        return True
    return None


def largest_face_size(extent: tuple[int, int], options: DrawingOptions) -> float:
    """Largest face size in 0.1 mm steps at which a net of ``extent`` faces fits the sheet (0 if none)."""
    x0, y0, x1, y1 = drawable_area(options)
    aw, ah = x1 - x0, y1 - y0
    ex, ey = max(extent[0], 1), max(extent[1], 1)
    # Tabs grow with the face up to tab_width: start from the bound without them and step down.
    p = math.floor(max(min(aw / ex, ah / ey), min(aw / ey, ah / ex)) * 10.0) / 10.0
    while p > 0 and fits(extent, options, p) is None:
        p = round(p - 0.1, 1)
    return max(p, 0.0)


def smallest_sheet(extent: tuple[int, int], options: DrawingOptions, pitch: float) -> str | None:
    """Name of the smallest sheet of :data:`SHEETS` that takes a net of ``extent`` faces at ``pitch``."""
    for name, size in sorted(SHEETS.items(), key=lambda kv: (kv[1][0] * kv[1][1], kv[0])):
        if fits(extent, options, pitch, size) is not None:
            return name
    return None


def extent_of(corners2d: npt.NDArray[np.int64]) -> tuple[int, int]:
    """Bounding box of a layout in faces."""
    c = corners2d.reshape(-1, 2)
    ex, ey = (c.max(axis=0) - c.min(axis=0)).tolist()
    return int(ex), int(ey)


def fit_error(extent: tuple[int, int], options: DrawingOptions, pitch: float, *, what: str) -> SheetFitError:
    """The error for a net of ``extent`` faces that does not fit the sheet at ``pitch``."""
    best = largest_face_size(extent, options)
    sheet = smallest_sheet(extent, options, pitch)
    needs = f"at {pitch:g} mm it needs {sheet}" if sheet else f"at {pitch:g} mm it is larger than every standard sheet"
    return SheetFitError(
        f"{what} spans {extent[0]} x {extent[1]} faces and does not fit sheet {options.sheet} at {pitch:g} mm "
        f"faces: it fits {options.sheet} at faces up to {best:g} mm, and {needs} (--sheet); or split it "
        "into pieces (--pieces auto)",
        extent=extent, largest_face_size=best, smallest_sheet=sheet,
    )


def _turned(c: npt.NDArray[np.int64], rotated: bool) -> npt.NDArray[np.int64]:
    if rotated:
        c = np.stack([-c[..., 1], c[..., 0]], axis=-1)
    return c - c.reshape(-1, 2).min(axis=0)


def auto_face_size(extent: tuple[int, int], options: DrawingOptions) -> float:
    """The face size of ``options`` or, when unset, the largest that fits a net of ``extent`` on one sheet."""
    if options.pitch is not None:
        return float(options.pitch)
    p = largest_face_size(extent, options)
    if p <= 0:
        raise InvalidShapeError(f"sheet: {options.sheet} has no room for a net inside a {options.margin:g} mm margin")
    return p


def plan_sheets(corners2d: npt.NDArray[np.int64], options: DrawingOptions, *, what: str = "the net") -> SheetPlan:
    """Put a net laid out at ``corners2d`` (F, 4, 2) cells on one sheet, turned if that fits better.

    Raises
    ------
    SheetFitError
        When it does not fit at the face size of ``options``.
    """
    extent = extent_of(corners2d)
    pitch = auto_face_size(extent, options)
    rotated = fits(extent, options, pitch)
    if rotated is None:
        raise fit_error(extent, options, pitch, what=what)
    x0, y0, x1, y1 = drawable_area(options)
    c = _turned(corners2d, rotated)
    ex, ey = c.reshape(-1, 2).max(axis=0)
    origin = np.array([[x0 + (x1 - x0 - ex * pitch) / 2, y0 + (y1 - y0 - ey * pitch) / 2]])
    return SheetPlan(pitch, rotated, c, np.zeros(c.shape[0], dtype=np.int64), origin, (x0, y0, x1, y1),
                     options.sheet_size)


def _quarter_turns(c: npt.NDArray[np.int64], turns: int) -> npt.NDArray[np.int64]:
    """``c`` turned ``turns`` quarter turns counter-clockwise, moved to start at cell (0, 0)."""
    for _ in range(turns % 4):
        c = np.stack([-c[..., 1], c[..., 0]], axis=-1)
    return c - c.reshape(-1, 2).min(axis=0)


def _mask(corners: npt.NDArray[np.int64]) -> npt.NDArray[np.bool_]:
    """``(w, h)`` cells covered by the faces at ``corners`` (n, 4, 2), which start at cell (0, 0)."""
    cells = corners.min(axis=1)
    w, h = corners.reshape(-1, 2).max(axis=0)
    m = np.zeros((int(w), int(h)), dtype=bool)
    m[cells[:, 0], cells[:, 1]] = True
    return m


def _grown(mask: npt.NDArray[np.bool_]) -> npt.NDArray[np.bool_]:
    """``mask`` and the cells beside it across an edge: where no face of another piece may lie."""
    g = mask.copy()
    g[1:] |= mask[:-1]
    g[:-1] |= mask[1:]
    g[:, 1:] |= mask[:, :-1]
    g[:, :-1] |= mask[:, 1:]
    return g


def _free_offsets(blocked: npt.NDArray[np.bool_], mask: npt.NDArray[np.bool_]) -> npt.NDArray[np.int64]:
    """``(k, 2)`` offsets at which ``mask`` meets no blocked cell of a sheet, bottom row first."""
    from numpy.lib.stride_tricks import sliding_window_view

    w, h = mask.shape
    if w > blocked.shape[0] or h > blocked.shape[1]:
        return np.zeros((0, 2), dtype=np.int64)
    windows = sliding_window_view(blocked, (w, h))
    hits = np.einsum("xyij,ij->xy", windows.astype(np.int32), mask.astype(np.int32))
    ox, oy = np.nonzero(hits == 0)
    order = np.lexsort((ox, oy))
    return np.stack([ox[order], oy[order]], axis=1).astype(np.int64)


def pack_pieces(pieces: list[npt.NDArray[np.int64]], options: DrawingOptions) -> tuple[SheetPlan, list[npt.NDArray[np.int64]]]:
    """Pack several pieces (their ``(n_i, 4, 2)`` corners in cells) on as few sheets as possible.

    The sheet is a raster of face cells (:func:`sheet_cells`, a tab's depth
    kept free all round).  The pieces go largest first, each in the first sheet
    that takes it, turned by the quarter turn and moved to the spot that keeps
    the sheet's filled rows lowest (then leftmost).  A piece's faces never lie
    on or beside (across an edge) a cell of another piece: every cell beside a
    piece stays free paper for its tabs, which go up to four to a cell, one
    from each side, without touching.

    Returns
    -------
    plan : SheetPlan
        For the faces of all pieces in order.
    placed : list of (n_i, 4, 2) int ndarray
        Each piece's corners in the plan's cells.

    Raises
    ------
    SheetFitError
        When a piece alone does not fit a sheet.
    """
    extents = [extent_of(c) for c in pieces]
    pitch = auto_face_size(max(extents, key=lambda e: e[0] * e[1]), options)
    cw, ch = sheet_cells(options, pitch)
    for e in extents:
        if fits(e, options, pitch) is None:
            raise fit_error(e, options, pitch, what="a piece")
    blocked: list[npt.NDArray[np.bool_]] = []
    where: dict[int, tuple[int, npt.NDArray[np.int64]]] = {}
    order = sorted(range(len(pieces)), key=lambda i: (-pieces[i].shape[0], i))
    for i in order:
        base = pieces[i] - pieces[i].reshape(-1, 2).min(axis=0)
        turns = [_quarter_turns(base, t) for t in range(4)]
        masks = [_mask(c) for c in turns]
        spot = None
        for s in range(len(blocked) + 1):
            if s == len(blocked):
                blocked.append(np.zeros((cw, ch), dtype=bool))
            best = None
            for t, m in enumerate(masks):
                offsets = _free_offsets(blocked[s], m)
                if offsets.shape[0] == 0:
                    continue
                tops = offsets[:, 1] + m.shape[1]
                j = int(np.lexsort((offsets[:, 0] + m.shape[0], tops))[0])
                key = (int(tops[j]), int(offsets[j, 0] + m.shape[0]), t)
                if best is None or key < best[0]:
                    best = (key, t, offsets[j])
            if best is not None:
                spot = (s, best[1], best[2])
                break
        assert spot is not None  # a piece that fits the sheet fits an empty one
        s, t, (ox, oy) = spot
        m = masks[t]
        grown = _grown(np.pad(m, 1))
        x0c, y0c = int(ox) - 1, int(oy) - 1
        gx0, gy0 = max(x0c, 0), max(y0c, 0)
        gx1, gy1 = min(x0c + grown.shape[0], cw), min(y0c + grown.shape[1], ch)
        blocked[s][gx0:gx1, gy0:gy1] |= grown[gx0 - x0c:gx1 - x0c, gy0 - y0c:gy1 - y0c]
        where[i] = (s, turns[t] + (int(ox), int(oy)))
    # Sheet s holds columns from s * stride on, so no two sheets share a cell.
    stride = cw + 2
    placed = [where[i][1] + (where[i][0] * stride, 0) for i in range(len(pieces))]
    sheets = [np.full(c.shape[0], where[i][0], dtype=np.int64) for i, c in enumerate(pieces)]
    x0, y0, x1, y1 = drawable_area(options)
    pad = tab_depth(options, pitch)
    left = x0 + pad + (x1 - x0 - 2 * pad - cw * pitch) / 2
    bottom = y0 + pad + (y1 - y0 - 2 * pad - ch * pitch) / 2
    origin = np.array([[left - s * stride * pitch, bottom] for s in range(len(blocked))], dtype=np.float64)
    plan = SheetPlan(pitch, False, np.concatenate(placed), np.concatenate(sheets), origin, (x0, y0, x1, y1),
                     options.sheet_size)
    return plan, placed
