"""Fitting a net on a sheet: automatic face size, a quarter turn, pieces packed on sheets.

A net goes on one sheet, turned a quarter turn when that fits better; when it
does not fit, :class:`SheetFitError` says the largest face size at which it
fits this sheet and the smallest standard sheet that takes it at this face
size.  Several pieces (``--pieces auto``) are packed cell by cell, turned by
quarter turns, on as few sheets as possible.
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import math
import threading
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError, UnfoldError

from ._legible import tab_depth
from ._options import SHEETS, DrawingOptions
from ._tabs import tab_heights


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
                 smallest_sheet: str | None, split: bool = True) -> None:
        super().__init__(message)
        self.extent = extent
        self.largest_face_size = largest_face_size
        self.smallest_sheet = smallest_sheet
        self.split = split

    @property
    def ways_out(self) -> list[dict[str, object]]:
        """The choices that would work, in plain words: ``[{"label": ..., "options": {NAME: VALUE}}]``."""
        return ways_out(self.largest_face_size, self.smallest_sheet, split=self.split)


def ways_out(largest: float, sheet: str | None, *, split: bool = True) -> list[dict[str, object]]:
    """Ways out of a net too large for its sheet: pieces (when ``split``: checked by the caller), the
    smallest sheet that takes it, smaller faces."""
    out: list[dict[str, object]] = [{"label": "split it into pieces", "options": {"pieces": "auto"}}] if split else []
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
    shift : (F, 2) float ndarray or None
        Offset in mm of each face from ``origin + corners2d * pitch``: pieces
        packed on a sheet sit at any millimetre, not only on whole cells.  The
        same for all faces of one piece.
    """

    pitch: float
    rotated: bool
    corners2d: npt.NDArray[np.int64]
    face_sheet: npt.NDArray[np.int64]
    origin: npt.NDArray[np.float64]
    area: tuple[float, float, float, float]
    size: tuple[float, float]
    shift: npt.NDArray[np.float64] | None = None

    @property
    def count(self) -> int:
        """Number of sheets."""
        return int(self.origin.shape[0])

    def face_positions(self) -> npt.NDArray[np.float64]:
        """``(F, 4, 2)`` face corners in mm on their own sheet."""
        return self.face_origin()[:, None, :] + self.corners2d * self.pitch

    def face_origin(self) -> npt.NDArray[np.float64]:
        """``(F, 2)`` position in mm of cell (0, 0) for each face: its sheet's origin plus its shift."""
        o = self.origin[self.face_sheet]
        return o if self.shift is None else o + self.shift


#: Pieces: a sheet is refused when the paper of the faces and of the fewest tabs a net can have
#: needs more sheets than this (:func:`pieces_sheets_at_least`, a bound no packing beats), or when it
#: is under :data:`PIECES_LEAST_ACROSS` faces across with their tabs.  Such sheets otherwise cost
#: minutes of search for a pile of slivers (the queen on a 60 x 60 mm sheet: 236 pieces on 162 sheets).
PIECES_MOST_SHEETS = 50
PIECES_LEAST_ACROSS = 2


class HopelessSheetError(UnfoldError):
    """A sheet too small for a net in pieces: too narrow, or more than :data:`PIECES_MOST_SHEETS` sheets.

    Attributes
    ----------
    largest_face_size : float
        Largest face size (mm, 0.1 mm steps, 0 when none) at which the sheet takes the pieces and the marks
        stay legible.
    smallest_sheet : str or None
        Smallest sheet of :data:`SHEETS` that takes them at the face size asked for.
    """

    def __init__(self, message: str, *, largest_face_size: float, smallest_sheet: str | None) -> None:
        super().__init__(message)
        self.largest_face_size = largest_face_size
        self.smallest_sheet = smallest_sheet

    @property
    def ways_out(self) -> list[dict[str, object]]:
        """A larger sheet, smaller faces: the same ways out as a net too large for one sheet, less the split."""
        return ways_out(self.largest_face_size, self.smallest_sheet, split=False)


def pieces_sheets_at_least(faces: int, options: DrawingOptions, pitch: float,
                           size: tuple[float, float] | None = None) -> int:
    """The fewest sheets that could take a net of ``faces`` faces of ``pitch`` mm: the paper of the faces and
    of a tab on each of the ``faces + 1`` seams a net has at least (its folds are a forest: at most
    ``faces - 1`` of the ``2 faces`` edges), over a sheet's drawable area."""
    from ._tabs import tab_heights

    x0, y0, x1, y1 = drawable_area(options, size)
    usable = max(x1 - x0, 0.0) * max(y1 - y0, 0.0)
    paper = faces * pitch * pitch
    if options.tabs:
        inset, h = tab_heights(pitch, options.tab_width, options.tab_angle)
        base = pitch - 2 * inset
        top = max(base - 2 * h / math.tan(math.radians(options.tab_angle)), 0.0)
        paper += (faces + 1) * (base + top) / 2 * h
    return math.ceil(paper / usable - 1e-9) if usable > 0 else math.inf


def pieces_problem(faces: int, options: DrawingOptions, pitch: float,
                   size: tuple[float, float] | None = None) -> str | None:
    """Why the sheet (or one of ``size`` mm) is hopeless for a net in pieces of ``faces`` faces of ``pitch``
    mm, or None when it is not."""
    cells = sheet_cells(options, pitch, size)
    if min(cells) < PIECES_LEAST_ACROSS:
        return (f"it takes {cells[0]} x {cells[1]} faces of {pitch:g} mm with their tabs, fewer than "
                f"{PIECES_LEAST_ACROSS} across")
    least = pieces_sheets_at_least(faces, options, pitch, size)
    if least > PIECES_MOST_SHEETS:
        return (f"the {faces} faces of {pitch:g} mm" + (" and their tabs" if options.tabs else "")
                + f" need at least {least} sheets (more than {PIECES_MOST_SHEETS})")
    return None


def check_pieces_sheet(faces: int, options: DrawingOptions, pitch: float, smallest: float) -> None:
    """Refuse, before any search, a sheet on which a net in pieces is hopeless (:data:`PIECES_MOST_SHEETS`).

    ``smallest`` is the smallest face size whose marks are legible; the error names the largest face size
    down to it that works, and the smallest standard sheet that works at ``pitch``.

    Raises
    ------
    HopelessSheetError
    """
    problem = pieces_problem(faces, options, pitch)
    if problem is None:
        return
    sheet = pieces_sheet(faces, options, pitch)
    best = 0.0
    p = math.floor(pitch * 10.0 - 1e-6) / 10.0
    while p >= smallest - 1e-9 and p > 0:
        if pieces_problem(faces, options, p) is None:
            best = p
            break
        p = round(p - 0.1, 1)
    outs = [f"use a larger sheet, {sheet} (--sheet)"] if sheet else []
    if best > 0:
        outs.append(f"make the faces {best:g} mm (--face-size)")
    raise HopelessSheetError(
        f"sheet {options.sheet} is too small for a net in pieces: {problem}; "
        + ("; or ".join(outs) if outs else "no standard sheet takes it at this face size"),
        largest_face_size=best, smallest_sheet=sheet)


def pieces_sheet(faces: int, options: DrawingOptions, pitch: float) -> str | None:
    """The smallest standard sheet that is not hopeless for a net in pieces at ``pitch`` (:func:`pieces_problem`)."""
    return next((name for name, size in sorted(SHEETS.items(), key=lambda kv: (kv[1][0] * kv[1][1], kv[0]))
                 if pieces_problem(faces, options, pitch, size) is None), None)


def drawable_area(options: DrawingOptions, size: tuple[float, float] | None = None) -> tuple[float, float, float, float]:
    """``(x0, y0, x1, y1)`` of the sheet inside the margin, above the title band, mm."""
    from voxfab.drawing import cutter_area

    w, h = options.sheet_size if size is None else size
    band = options.title_height + 2.0 if options.heading else 0.0
    x0, y0, x1, y1 = cutter_area(options.cutter, (w, h), float(options.margin))
    # The title band lies under the art, inside the margin (a Cricut's area may leave room below it).
    return (x0, max(y0, options.edge + band), x1, y1)


@dataclasses.dataclass(frozen=True)
class Paper:
    """A sheet at one face size, worked out once: what the net search, the packer, the placement check
    and the drawing all read (:func:`paper`).

    Attributes
    ----------
    pitch : float
        Face edge, mm.
    size : (float, float)
        Sheet width and height, mm.
    area : (float, float, float, float)
        ``(x0, y0, x1, y1)`` drawable rectangle: inside the margin, above the title band, mm.
    tab_depth : float
        Height of a full glue tab, mm (0 without tabs).
    cells : (int, int)
        Faces across and down the drawable area with a tab all round (the ``fit`` of the net search).
    per_cell : int
        Packing raster steps per face edge (about :data:`_STEP_MM` each).
    step : float
        Packing raster step, mm.
    clear : int
        Steps of paper kept free round every packed piece (:data:`_CLEARANCE_MM` at least).
    raster : (int, int)
        The drawable area in steps.
    tab_steps : int
        Steps a tab band takes beyond its edge on the raster.
    tab_trim : tuple of int
        Per row of a tab band (from the edge out), the steps left off at each end: a tab narrows as it
        leaves its edge, so two pieces' tabs nest at their corners.
    """

    pitch: float
    size: tuple[float, float]
    area: tuple[float, float, float, float]
    tab_depth: float
    cells: tuple[int, int]
    per_cell: int
    step: float
    clear: int
    raster: tuple[int, int]
    tab_steps: int
    tab_trim: tuple[int, ...] = ()


def paper(options: DrawingOptions, pitch: float, size: tuple[float, float] | None = None) -> Paper:
    """The sheet of ``options`` (or of ``size``, mm) at face size ``pitch``, made once per options and size."""
    return _paper(options, float(pitch), None if size is None else (float(size[0]), float(size[1])))


@functools.lru_cache(maxsize=256)
def _paper(options: DrawingOptions, pitch: float, size: tuple[float, float] | None) -> Paper:
    x0, y0, x1, y1 = area = drawable_area(options, size)
    pad = tab_depth(options, pitch)
    w, h = x1 - x0 - 2 * pad, y1 - y0 - 2 * pad
    cells = (max(int(math.floor(w / pitch + 1e-9)), 0), max(int(math.floor(h / pitch + 1e-9)), 0))
    k = max(2, int(round(pitch / _STEP_MM)))
    step = pitch / k
    clear = max(1, int(math.ceil(_CLEARANCE_MM / step - 1e-9)))
    raster = (int(math.floor((x1 - x0) / step + 1e-9)), int(math.floor((y1 - y0) / step + 1e-9)))
    depth = int(math.ceil(pad / step - 1e-9))
    inset = tab_heights(pitch, options.tab_width, options.tab_angle)[0]
    run = 1.0 / math.tan(math.radians(options.tab_angle))
    # Row j's near side is the tab's widest there: it starts inset + j step / tan(angle) along the edge.
    trim = tuple(min(int(math.floor((inset + j * step * run) / step - 1e-9)), (k - 1) // 2) for j in range(depth))
    return Paper(float(pitch), options.sheet_size if size is None else size, area, pad, cells, k, step, clear,
                 raster, depth, trim)


def sheet_cells(options: DrawingOptions, pitch: float, size: tuple[float, float] | None = None) -> tuple[int, int]:
    """Faces across and down a sheet at face size ``pitch`` (the ``fit`` of the net search)."""
    return paper(options, pitch, size).cells


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


def fit_error(extent: tuple[int, int], options: DrawingOptions, pitch: float, *, what: str,
              found: tuple[int, int] | None = None, split: bool = True) -> SheetFitError:
    """The error for a net of ``extent`` faces that does not fit the sheet at ``pitch``.

    ``found`` is the extent of the net the search of the automatic face size found to fit at the
    largest face size (:func:`._fit.largest_fitting`): the face size and sheet named are measured from
    it when it fits better, so every refusal agrees with that search.  ``split``: offer pieces (the
    caller checked that pieces pass at ``pitch``).
    """
    best = largest_face_size(extent, options)
    sheet = smallest_sheet(extent, options, pitch)
    fits_at = f"it fits {options.sheet} at faces up to {best:g} mm"
    if found is not None and largest_face_size(found, options) > best:
        best = largest_face_size(found, options)
        sheet = sheet or smallest_sheet(found, options, pitch)
        fits_at = f"a one-piece net was found that fits {options.sheet} at faces up to {best:g} mm"
    needs = f"at {pitch:g} mm it needs {sheet}" if sheet else f"at {pitch:g} mm it is larger than every standard sheet"
    return SheetFitError(
        f"{what} spans {extent[0]} x {extent[1]} faces and does not fit sheet {options.sheet} at {pitch:g} mm "
        f"faces: {fits_at}, and {needs} (--sheet)" + ("; or split it into pieces (--pieces auto)" if split else ""),
        extent=extent, largest_face_size=best, smallest_sheet=sheet, split=split,
    )


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
    x0, y0, x1, y1 = paper(options, pitch).area
    c = _quarter_turns(corners2d, 1 if rotated else 0)
    ex, ey = c.reshape(-1, 2).max(axis=0)
    origin = np.array([[x0 + (x1 - x0 - ex * pitch) / 2, y0 + (y1 - y0 - ey * pitch) / 2]])
    return SheetPlan(pitch, rotated, c, np.zeros(c.shape[0], dtype=np.int64), origin, (x0, y0, x1, y1),
                     options.sheet_size)


def _quarter_turns(c: npt.NDArray[np.int64], turns: int) -> npt.NDArray[np.int64]:
    """``c`` turned ``turns`` quarter turns counter-clockwise, moved to start at cell (0, 0)."""
    for _ in range(turns % 4):
        c = np.stack([-c[..., 1], c[..., 0]], axis=-1)
    return c - c.reshape(-1, 2).min(axis=0)


#: Raster step of packing, about this many mm: pieces and their tabs are
#: rasterized at a whole fraction of the face size, so faces stay on it.  At
#: 2 mm the queen, pawn, egg and vase pack on as many A4 sheets as at 1 mm, in
#: a fifth of the time (a tab takes at most a step more than its depth).
_STEP_MM = 2.0
#: Clear paper between two pieces (with their tabs) on a sheet, mm at least.
_CLEARANCE_MM = 1.0


@dataclasses.dataclass(frozen=True, eq=False)
class _Shape:
    """One piece turned a number of quarter turns, as a raster mask.

    ``corners`` are its face corners in cells from (0, 0); ``mask`` its faces
    and reserved tabs in steps, whose step (0, 0) is at ``start`` steps from
    the piece's cell (0, 0).
    """

    corners: npt.NDArray[np.int64]
    mask: npt.NDArray[np.bool_]
    start: tuple[int, int]


def _edge_normals(corners: npt.NDArray[np.int64], edges: npt.NDArray[np.int64]
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Both ends ``(n, 2)`` and the outward unit normal ``(n, 2)`` of ``edges`` (face, edge) of faces at ``corners``."""
    f, k = edges[:, 0], edges[:, 1]
    p0 = corners[f, k]
    p1 = corners[f, (k + 1) % 4]
    d = p1 - p0
    # Faces run counter-clockwise: outside is on the right of each edge.
    return p0, p1, np.stack([d[:, 1], -d[:, 0]], axis=1)


def _shape(corners: npt.NDArray[np.int64], tab_edges: npt.NDArray[np.int64], k: int, depth: int,
           trim: tuple[int, ...] = ()) -> _Shape:
    """The raster of a piece at ``k`` steps per cell: its faces and a band ``depth`` steps deep per tab edge,
    its row ``j`` out from the edge ``trim[j]`` steps shorter at both ends (the tab's trapezoid, covered)."""
    lo = corners.reshape(-1, 2).min(axis=0)
    c = corners - lo
    w, h = (c.reshape(-1, 2).max(axis=0) + 2) * k  # a cell of room all round for tabs
    m = np.zeros((int(w), int(h)), dtype=bool)
    for x, y in (c.min(axis=1) + 1).tolist():
        m[x * k:(x + 1) * k, y * k:(y + 1) * k] = True
    if tab_edges.size:
        p0, p1, n = _edge_normals(c + 1, tab_edges)
        a = np.minimum(p0, p1) * k
        b = np.maximum(p0, p1) * k
        along = np.sign(b - a)
        # Row j of a band on a vertical edge spans the edge's steps less trim[j] at each end, one step
        # wide, j steps out; and so on.
        for j in range(depth):
            t = trim[j] if j < len(trim) else 0
            lo_b = np.minimum(a + n * j, a + n * (j + 1)) + along * t
            hi_b = np.maximum(b + n * j, b + n * (j + 1)) - along * t
            for (x0, y0), (x1, y1) in zip(lo_b.tolist(), hi_b.tolist()):
                m[x0:x1, y0:y1] = True
    xs, ys = np.nonzero(m)
    x0, y0 = int(xs.min()), int(ys.min())
    return _Shape(c, m[x0:xs.max() + 1, y0:ys.max() + 1], (x0 - k, y0 - k))


def _dilated(mask: npt.NDArray[np.bool_], r: int) -> npt.NDArray[np.bool_]:
    """``mask`` grown by ``r`` steps each way (a square), padded by ``r`` all round."""
    out = np.zeros((mask.shape[0] + 2 * r, mask.shape[1] + 2 * r), dtype=bool)
    for dx in range(2 * r + 1):
        for dy in range(2 * r + 1):
            out[dx:dx + mask.shape[0], dy:dy + mask.shape[1]] |= mask
    return out


class _Spectra:
    """A piece turned one way, ready for the packer: its mask, the ring of steps just round it, and both
    flipped and transformed once (their spectra on a sheet's raster), for every sheet and every try."""

    def __init__(self, shape: _Shape, raster: tuple[int, int]) -> None:
        mask = shape.mask
        self.shape = shape
        self.size = int(mask.sum())
        ring = _dilated(mask, 1) & ~np.pad(mask, 1)
        self.mask = np.fft.rfft2(mask[::-1, ::-1].astype(np.float64), s=_fast(raster))
        self.ring = np.fft.rfft2(ring[::-1, ::-1].astype(np.float64), s=_fast((raster[0] + 2, raster[1] + 2)))

    def facing(self, corners: npt.NDArray[np.int64]) -> _Spectra:
        """The same, for the piece as ``corners`` lists its faces (turned this way, from cell (0, 0))."""
        out = copy.copy(self)
        out.shape = dataclasses.replace(self.shape, corners=corners)
        return out


@functools.lru_cache(maxsize=256)
def _fast(size: tuple[int, int]) -> tuple[int, int]:
    """A transform size at least ``size`` that factors into small primes: A5's raster is 59 steps wide (a prime),
    which transforms three times slower.  Zeros padded past the raster change no correlation on the offsets
    where a mask lies inside it.  Each side the least 2^i 3^j 5^k at least it: scipy.fft's next_fast_len(n, real=True)
    without loading scipy.fft (a tenth of a second of a net's run)."""
    odd = [3 ** j * 5 ** k for j in range(12) for k in range(9)]
    a, b = (min(p << max(-(-int(n) // p) - 1, 0).bit_length() for p in odd) for n in size)
    return a, b


class _Sheet:
    """A sheet being packed: its blocked steps, and their spectra computed once after each change."""

    def __init__(self, raster: tuple[int, int]) -> None:
        self.raster = raster
        self.blocked = np.zeros(raster, dtype=bool)
        self.free = raster[0] * raster[1]
        self._spectra: tuple[np.ndarray, np.ndarray] | None = None

    def block(self, grown: npt.NDArray[np.bool_], gx: int, gy: int) -> None:
        """Block ``grown`` with its step (0, 0) at step ``(gx, gy)``, clipped to the sheet."""
        a0, b0 = max(gx, 0), max(gy, 0)
        a1, b1 = min(gx + grown.shape[0], self.raster[0]), min(gy + grown.shape[1], self.raster[1])
        self.blocked[a0:a1, b0:b1] |= grown[a0 - gx:a1 - gx, b0 - gy:b1 - gy]
        self.free = int(self.blocked.size - np.count_nonzero(self.blocked))
        self._spectra = None

    def fill(self) -> None:
        self.blocked[:] = True
        self.free = 0
        self._spectra = None

    def spectra(self) -> tuple[np.ndarray, np.ndarray]:
        """The blocked steps, and them walled by the sheet's edge, transformed (circular correlation on the
        raster is exact on the offsets where a mask lies inside it)."""
        if self._spectra is None:
            walled = np.pad(self.blocked, 1, constant_values=True)
            self._spectra = (np.fft.rfft2(self.blocked.astype(np.float64), s=_fast(self.raster)),
                             np.fft.rfft2(walled.astype(np.float64), s=_fast((walled.shape[0], walled.shape[1]))))
        return self._spectra


def _best_spots(sheet: _Sheet, turns: list[_Spectra], touch: bool = True
                ) -> list[tuple[int, int, int, int] | None]:
    """Where each turn of a piece meets no blocked step of ``sheet`` and touches most of them:
    ``(-touch, top, ox, oy)`` per turn, None where a turn has no spot.

    Touch counts the blocked steps (the sheet's edge counting as blocked)
    just round the mask: a piece that hugs the others and the edge leaves the
    fewest slivers of paper between them.  Ties go to the lowest top, then
    the leftmost spot.  Without ``touch``: the lowest top, then the leftmost
    right, ``(top, right, ox, oy)``.  The turns' correlations are transformed
    together, one call for all (the transforms are the same, line by line).
    """
    big_w, big_h = sheet.raster
    out: list[tuple[int, int, int, int] | None] = [None] * len(turns)
    live = [t for t, piece in enumerate(turns) if piece.shape.mask.shape[0] <= big_w
            and piece.shape.mask.shape[1] <= big_h and piece.size <= sheet.free]
    if not live:
        return out
    blocked, walled = sheet.spectra()
    # Overlap counts for every offset at once (a correlation), exact in floats up to rounding.
    hits = np.fft.irfft2(blocked * np.stack([turns[t].mask for t in live]), s=_fast(sheet.raster), axes=(-2, -1))
    free: list[tuple[int, npt.NDArray[np.int64], npt.NDArray[np.int64]]] = []
    for k, t in enumerate(live):
        w, h = turns[t].shape.mask.shape
        ox, oy = np.nonzero(hits[k, w - 1:big_w, h - 1:big_h] < 0.5)
        if ox.size == 0:
            continue
        if not touch:
            j = int(np.lexsort((ox + w, oy + h))[0])
            out[t] = (int(oy[j]) + h, int(ox[j]) + w, int(ox[j]), int(oy[j]))
        else:
            free.append((t, ox, oy))
    if not free:
        return out
    near = np.fft.irfft2(walled * np.stack([turns[t].ring for t, _, _ in free]), s=_fast((big_w + 2, big_h + 2)),
                         axes=(-2, -1))
    for k, (t, ox, oy) in enumerate(free):
        w, h = turns[t].shape.mask.shape
        n = np.rint(near[k, w + 1:big_w + 2, h + 1:big_h + 2][ox, oy]).astype(np.int64)
        j = int(np.lexsort((ox, oy + h, -n))[0])
        out[t] = (-int(n[j]), int(oy[j]) + h, int(ox[j]), int(oy[j]))
    return out


def _pack_once(pieces: list[list[_Spectra]], order: list[int], raster: tuple[int, int], clear: int,
               touch: bool, sheets: list[_Sheet] | None = None) -> tuple[int, dict]:
    """One packing of the pieces in ``order``: the sheets used, and per piece ``(sheet, shape, offset)``.

    The offset (in steps) is that of the piece's cell (0, 0); shape None for a
    piece that meets no spot even on an empty sheet (it gets a sheet alone).
    ``sheets`` are sheets already part filled (a re-layout's), taken first and
    changed in place.
    """
    from voxfab._shared.progress import check_cancelled

    sheets = [] if sheets is None else sheets
    where: dict[int, tuple[int, _Shape | None, tuple[int, int]]] = {}
    for i in order:
        check_cancelled()  # between pieces: a cancelled studio job stops within one piece's spot search
        spot = None
        for s in range(len(sheets) + 1):
            if s == len(sheets):
                sheets.append(_Sheet(raster))
            best = None
            for t, found in enumerate(_best_spots(sheets[s], pieces[i], touch)):
                if found is not None and (best is None or found[:2] + (t,) < best[0]):
                    best = (found[:2] + (t,), t, found[2:])
            if best is not None:
                spot = (s, best[1], best[2])
                break
            if sheets[s].free == raster[0] * raster[1]:  # even an empty sheet has no spot for it
                break
        if spot is None:
            s = len(sheets) - 1
            sheets[s].fill()
            where[i] = (s, None, (0, 0))
            continue
        s, t, (ox, oy) = spot
        sh = pieces[i][t].shape
        sheets[s].block(_dilated(sh.mask, clear), ox - clear, oy - clear)
        where[i] = (s, sh, (ox - sh.start[0], oy - sh.start[1]))
    return len(sheets), where


def _orders(faces: list[int], shapes: list[list[_Spectra]]) -> tuple[Callable[[int], tuple[int, int]], ...]:
    """The orders the packer tries, largest first, as sort keys of a piece's index: by faces, by paper, by
    bounding box (ties by index)."""
    area = [sh[0].size for sh in shapes]
    box = [sh[0].shape.mask.shape[0] * sh[0].shape.mask.shape[1] for sh in shapes]
    return (lambda i: (-faces[i], i), lambda i: (-area[i], i), lambda i: (-box[i], i))


def _spot_mm(corners: npt.NDArray[np.int64], shape: _Shape | None, at: tuple[int, int], options: DrawingOptions,
             sheet: Paper) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]:
    """A packed piece's corners as it lies (turned, from cell (0, 0)) and the mm from the drawable area's corner
    to its cell (0, 0); a piece without a ``shape`` (no spot even on an empty sheet) alone, centred."""
    if shape is not None:
        return shape.corners, np.asarray(at, dtype=np.float64) * sheet.step
    x0, y0, x1, y1 = sheet.area
    ex, ey = _quarter_turns(corners, 0).reshape(-1, 2).max(axis=0)
    c = _quarter_turns(corners, 1 if fits((int(ex), int(ey)), options, sheet.pitch) else 0)
    ex, ey = c.reshape(-1, 2).max(axis=0)
    return c, np.array([(x1 - x0 - ex * sheet.pitch) / 2, (y1 - y0 - ey * sheet.pitch) / 2])


def piece_mask(corners: npt.NDArray[np.int64], tab_edges: npt.NDArray[np.int64], options: DrawingOptions,
               pitch: float) -> tuple[npt.NDArray[np.bool_], tuple[int, int]]:
    """A piece (its corners in cells, as it lies) as the packer sees it: its raster mask of faces and tab
    bands, and the step of the mask's (0, 0) from the piece's lowest cell corner."""
    p = paper(options, pitch)
    shape = _shape(corners, tab_edges, p.per_cell, p.tab_steps, p.tab_trim)
    return shape.mask, shape.start


def dilated(mask: npt.NDArray[np.bool_], r: int) -> npt.NDArray[np.bool_]:
    """``mask`` grown by ``r`` steps each way (a square), padded by ``r`` all round: the packer's clearance."""
    return _dilated(mask, r)


#: The last packings made, by their pieces, tabs and options: pieces laid out for the studio's
#: gallery, or measured by :func:`._drawing.sheets_needed`, are drawn on the same packing, not packed again.
_PACKED: dict[bytes, tuple[SheetPlan, list[npt.NDArray[np.int64]]]] = {}
_PACKED_KEPT = 4
_PACKED_LOCK = threading.Lock()  # studio jobs pack on worker threads


def _packing_key(pieces: list[npt.NDArray[np.int64]], options: DrawingOptions,
                 tab_edges: list[npt.NDArray[np.int64]] | None) -> bytes:
    import hashlib

    h = hashlib.sha256(repr(options).encode())
    for i, c in enumerate(pieces):
        h.update(np.ascontiguousarray(c, dtype=np.int64).tobytes() + b"|" + str(c.shape).encode())
        if tab_edges is not None:
            h.update(b"t" + np.ascontiguousarray(tab_edges[i], dtype=np.int64).tobytes() + str(tab_edges[i].shape).encode())
    return h.digest()


def pack_pieces(pieces: list[npt.NDArray[np.int64]], options: DrawingOptions,
                tab_edges: list[npt.NDArray[np.int64]] | None = None,
                ) -> tuple[SheetPlan, list[npt.NDArray[np.int64]]]:
    """Pack several pieces (their ``(n_i, 4, 2)`` corners in cells) on as few sheets as possible.

    Each piece is a raster mask of about :data:`_STEP_MM` a step: its faces and,
    for each edge of ``tab_edges`` (its ``(t_i, 2)`` face and edge pairs that
    take a glue tab), a band a full tab deep beyond the edge.  Pieces go largest
    first, each on the first sheet that takes it, turned by the quarter turn
    and moved to the spot whose top is lowest (then whose right is leftmost),
    with :data:`_CLEARANCE_MM` of paper kept free round every other piece.
    Three orders (by faces, by paper, by bounding box) and two rules (most
    touch, lowest top) are tried, and the packing on the fewest sheets kept
    (the bounding box order saves the pawn a sheet on A4).  So
    tabs of two pieces interleave in the gap between them, and a piece fills a
    notch of another.  A piece that meets no spot even on an empty sheet (its
    tabs need a step more than the room) goes on a sheet of its own, centred.

    Returns
    -------
    plan : SheetPlan
        For the faces of all pieces in order; each piece's cells lie apart from
        every other piece's (two cells at least), its place on the sheet is its
        faces' ``shift``.
    placed : list of (n_i, 4, 2) int ndarray
        Each piece's corners in the plan's cells.

    Raises
    ------
    SheetFitError
        When a piece alone does not fit a sheet.
    """
    key = _packing_key(pieces, options, tab_edges)
    with _PACKED_LOCK:
        known = _PACKED.get(key)
    if known is not None:
        return known
    packed = _pack_pieces(pieces, options, tab_edges)
    with _PACKED_LOCK:
        _PACKED[key] = packed
        while len(_PACKED) > _PACKED_KEPT:
            del _PACKED[next(iter(_PACKED))]
    return packed


#: Each piece's four turns as the packer sees them, by the piece (its cells, in any order, anywhere), its
#: tabs and the raster: after a cut or a join only the pieces it changed are transformed again (a tenth of a
#: second on the queen's 35 pieces), though the edit lists their faces in another order.
_TURNS: dict[bytes, list[_Spectra]] = {}
_TURNS_KEPT = 64
_TURNS_LOCK = threading.Lock()


def _turns(corners: npt.NDArray[np.int64], tab_edges: npt.NDArray[np.int64], per_cell: int, tab_steps: int,
           raster: tuple[int, int], tab_trim: tuple[int, ...] = ()) -> list[_Spectra]:
    """The four quarter turns of a piece, ready for the packer (the same arrays for the same piece)."""
    import hashlib

    h = hashlib.sha256(repr((per_cell, tab_steps, tuple(raster), tuple(tab_trim), corners.shape,
                             tab_edges.shape)).encode())
    rows = (corners - corners.reshape(-1, 2).min(axis=0)).reshape(corners.shape[0], -1).astype(np.int64)
    order = np.lexsort(rows.T[::-1])
    tabs = np.column_stack([np.argsort(order)[tab_edges[:, 0]], tab_edges[:, 1]]).astype(np.int64)
    h.update(rows[order].tobytes() + tabs[np.lexsort(tabs.T[::-1])].tobytes())
    key = h.digest()
    with _TURNS_LOCK:
        known = _TURNS.pop(key, None)
        if known is not None:
            _TURNS[key] = known  # most recently used last
            return [s.facing(_quarter_turns(corners, t)) for t, s in enumerate(known)]
    # A quarter turn keeps each face's corner order, so the tab edges stay the same pairs.
    made = [_Spectra(_shape(_quarter_turns(corners, t), tab_edges, per_cell, tab_steps, tab_trim), raster)
            for t in range(4)]
    with _TURNS_LOCK:
        _TURNS[key] = made
        while len(_TURNS) > _TURNS_KEPT:
            del _TURNS[next(iter(_TURNS))]
    return made


def _pack_pieces(pieces: list[npt.NDArray[np.int64]], options: DrawingOptions,
                 tab_edges: list[npt.NDArray[np.int64]] | None) -> tuple[SheetPlan, list[npt.NDArray[np.int64]]]:
    extents = [extent_of(c) for c in pieces]
    pitch = auto_face_size(max(extents, key=lambda e: e[0] * e[1]), options)
    for e in extents:
        if fits(e, options, pitch) is None:
            raise fit_error(e, options, pitch, what="a piece", split=False)
    if tab_edges is None:
        tab_edges = [np.zeros((0, 2), dtype=np.int64) for _ in pieces]
    sheet = paper(options, pitch)
    clear, raster = sheet.clear, sheet.raster
    x0, y0, x1, y1 = sheet.area
    shapes = [_turns(c, tab_edges[i], sheet.per_cell, sheet.tab_steps, raster, sheet.tab_trim)
              for i, c in enumerate(pieces)]
    least = math.ceil(sum(sh[0].size for sh in shapes) / (raster[0] * raster[1]))
    where: dict[int, tuple[int, npt.NDArray[np.int64], npt.NDArray[np.float64]]] = {}
    count = 0
    # Orders and rules tried in turn, the fewest sheets kept (the first on a tie); a packing on as
    # few sheets as the paper needs ends the tries.
    for touch in (True, False):
        for by in _orders([c.shape[0] for c in pieces], shapes):
            n, spots = _pack_once(shapes, sorted(range(len(pieces)), key=by), raster, clear, touch)
            if not where or n < count:
                count, where = n, spots
            if count <= least:
                break
        if count <= least:
            break
    for i, (s, sh, at) in list(where.items()):
        where[i] = (s, *_spot_mm(pieces[i], sh, at, options, sheet))
    # Each piece in cells of its own, two cells apart from the next: no two
    # pieces ever share or touch a cell, so edges of different pieces never meet.
    placed, sheets, shifts = [], [], []
    bx = 0
    for i, c in enumerate(pieces):
        s, corners, at = where[i]
        placed.append(corners + (bx, 0))
        sheets.append(np.full(c.shape[0], s, dtype=np.int64))
        shifts.append(np.tile(at - (bx * pitch, 0.0), (c.shape[0], 1)))
        bx += int(corners[..., 0].max()) + 2
    origin = np.tile([x0, y0], (count, 1)).astype(np.float64)
    plan = SheetPlan(pitch, False, np.concatenate(placed), np.concatenate(sheets), origin, (x0, y0, x1, y1),
                     options.sheet_size, np.concatenate(shifts))
    return plan, placed
