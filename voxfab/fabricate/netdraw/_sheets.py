"""Fitting a net on sheets: automatic pitch, a quarter turn, or a split over several sheets."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError

from ._options import DrawingOptions


@dataclasses.dataclass(frozen=True, eq=False)
class SheetPlan:
    """Where every face goes.

    Attributes
    ----------
    pitch : float
        Face edge length, mm.
    rotated : bool
        The net is turned a quarter turn counter-clockwise to fit better.
    corners2d : (F, 4, 2) int ndarray
        Face corners in cells after the turn, with the net's lower-left cell at 0.
    face_sheet : (F,) int ndarray
        Sheet index of each face.
    origin : (S, 2) float ndarray
        Position in mm of cell (0, 0) on each sheet.
    windows : (S, 2) int ndarray
        Column and row of each sheet's window over the net (0, 0 on one sheet).
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
    windows: npt.NDArray[np.int64]
    area: tuple[float, float, float, float]
    size: tuple[float, float]

    @property
    def count(self) -> int:
        """Number of sheets."""
        return int(self.origin.shape[0])

    def face_positions(self) -> npt.NDArray[np.float64]:
        """``(F, 4, 2)`` face corners in mm on their own sheet."""
        return self.origin[self.face_sheet][:, None, :] + self.corners2d * self.pitch


def drawable_area(options: DrawingOptions) -> tuple[float, float, float, float]:
    """``(x0, y0, x1, y1)`` of the sheet inside the margin, above the title band, mm."""
    w, h = options.sheet_size
    m = float(options.margin)
    band = options.title_height + 2.0 if options.heading else 0.0
    return (m, m + band, w - m, h - m)


def _turned(c: npt.NDArray[np.int64], rotated: bool) -> npt.NDArray[np.int64]:
    if rotated:
        c = np.stack([-c[..., 1], c[..., 0]], axis=-1)
    return c - c.reshape(-1, 2).min(axis=0)


def plan_sheets(corners2d: npt.NDArray[np.int64], options: DrawingOptions) -> SheetPlan:
    """Choose pitch, turn and sheets for a net laid out at ``corners2d`` (F, 4, 2) cells.

    With ``options.pitch`` set, the net goes on one sheet when it fits either way
    round, else on the fewest sheets of a regular split.  Without a pitch, the
    largest pitch that fits one sheet is used, unless it is below
    ``options.min_auto_pitch``: then that minimum is used and the net is split.

    Raises
    ------
    InvalidShapeError
        When one face with its tabs is larger than the drawable area.
    """
    x0, y0, x1, y1 = drawable_area(options)
    aw, ah = x1 - x0, y1 - y0
    pad = float(options.tab_width)
    ext = corners2d.reshape(-1, 2).max(axis=0) - corners2d.reshape(-1, 2).min(axis=0)
    orient = [(False, int(ext[0]), int(ext[1])), (True, int(ext[1]), int(ext[0]))]
    pitch = options.pitch
    if pitch is None:
        best = max(orient, key=lambda o: (min((aw - 2 * pad) / o[1], (ah - 2 * pad) / o[2]), not o[0]))
        p = math.floor(min((aw - 2 * pad) / best[1], (ah - 2 * pad) / best[2]) * 10.0 + 1e-9) / 10.0
        if p >= options.min_auto_pitch:
            return _single(corners2d, best[0], p, options)
        pitch = float(options.min_auto_pitch)
    pitch = float(pitch)
    eps = 1e-9
    for rotated, ex, ey in orient:
        if ex * pitch + 2 * pad <= aw + eps and ey * pitch + 2 * pad <= ah + eps:
            return _single(corners2d, rotated, pitch, options)
    cw = int(math.floor((aw - 2 * pad) / pitch + eps))
    ch = int(math.floor((ah - 2 * pad) / pitch + eps))
    if cw < 1 or ch < 1:
        raise InvalidShapeError(
            f"pitch: {pitch:g} mm faces with {pad:g} mm tabs do not fit on sheet {options.sheet} "
            f"inside a {options.margin:g} mm margin"
        )
    rotated = min(orient, key=lambda o: (math.ceil(o[1] / cw) * math.ceil(o[2] / ch), o[0]))[0]
    c = _turned(corners2d, rotated)
    cell = c.min(axis=1)
    size = np.array([cw, ch])
    win, phase = _windows(cell, size)
    # Reading order: top row of windows first, left to right.
    keys = np.unique(np.stack([-win[:, 1], win[:, 0]], axis=1), axis=0)
    windows = np.stack([keys[:, 1], -keys[:, 0]], axis=1)
    lookup = {(int(a), int(b)): i for i, (a, b) in enumerate(windows)}
    face_sheet = np.array([lookup[(int(a), int(b))] for a, b in win], dtype=np.int64)
    left = x0 + pad + (aw - 2 * pad - cw * pitch) / 2
    bottom = y0 + pad + (ah - 2 * pad - ch * pitch) / 2
    origin = np.stack([left - windows[:, 0] * cw * pitch, bottom - windows[:, 1] * ch * pitch], axis=1)
    origin = origin + phase * pitch
    return SheetPlan(pitch, rotated, c, face_sheet, origin.astype(np.float64), windows, (x0, y0, x1, y1),
                     options.sheet_size)


def _windows(
    cell: npt.NDArray[np.int64], size: npt.NDArray[np.int64]
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    """Window (column, row) of each face cell, and the shift of the window grid that needs the fewest sheets.

    Cell ``c`` falls in window ``(c + shift) // size``.
    """
    best: tuple[int, int, int] | None = None
    steps = [np.unique(np.linspace(0, n - 1, min(n, 8)).astype(np.int64)) for n in size.tolist()]
    for ox in steps[0].tolist():
        for oy in steps[1].tolist():
            w = (cell + (ox, oy)) // size
            count = np.unique(w[:, 0] * (int(w[:, 1].max()) + 1) + w[:, 1]).size
            if best is None or count < best[0]:
                best = (count, ox, oy)
    assert best is not None
    shift = np.array(best[1:], dtype=np.int64)
    return (cell + shift) // size, shift


def _single(corners2d: npt.NDArray[np.int64], rotated: bool, pitch: float, options: DrawingOptions) -> SheetPlan:
    x0, y0, x1, y1 = drawable_area(options)
    c = _turned(corners2d, rotated)
    ex, ey = c.reshape(-1, 2).max(axis=0)
    origin = np.array([[x0 + (x1 - x0 - ex * pitch) / 2, y0 + (y1 - y0 - ey * pitch) / 2]])
    return SheetPlan(pitch, rotated, c, np.zeros(c.shape[0], dtype=np.int64), origin,
                     np.zeros((1, 2), dtype=np.int64), (x0, y0, x1, y1), options.sheet_size)
