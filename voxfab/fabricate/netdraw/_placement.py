"""Where the pieces of a net sit on their sheets, as data: read from a packing, or given to draw a net.

A :class:`Placement` says, for every piece, its sheet, its quarter turns and
where its own frame's origin lands on the sheet in mm (origin at the sheet's
lower-left corner).  :func:`placement_of` reads one from a
:class:`~._sheets.SheetPlan` (what the packer chose); :func:`plan_placement`
turns one back into a plan the drawing code draws, after checking that the
pieces with their glue tabs stay inside the margin and keep clear of each
other, by the packer's own raster masks and clearance.

The studio's page moves and turns pieces by whole faces, so every piece stays
on the packing raster: a piece off it is refused, as is a mirrored piece
(printed mirrored, its folds would turn inside out).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab.errors import InvalidShapeError

from ._options import DrawingOptions
from ._sheets import SheetPlan

#: Slack of the grid and margin checks, mm (JSON round trips of decimal mm).
TOLERANCE = 1e-6


class PlacementError(InvalidShapeError):
    """A placement that cannot be drawn: malformed, off the grid, overlapping, or across the margin."""


@dataclasses.dataclass(frozen=True)
class PiecePlace:
    """Where one piece goes.

    Attributes
    ----------
    piece : int
        0-based piece index (the order of the net's pieces).
    sheet : int
        0-based sheet index.
    x, y : float
        Where the piece frame's origin lands on the sheet, mm, after the turns.
    turns : int
        Quarter turns counter-clockwise, 0 to 3.
    mirror : bool
        Mirrored (x -> -x before turning); always False for a drawable net.
    """

    piece: int
    sheet: int
    x: float
    y: float
    turns: int = 0
    mirror: bool = False


@dataclasses.dataclass(frozen=True)
class Placement:
    """Every piece of a net on its sheet.

    Attributes
    ----------
    sheet : (float, float)
        Sheet width and height, mm.
    margin : float
        Empty border of every sheet, mm.
    face_size : float
        Face edge, mm.
    sheets : int
        Number of sheets.
    pieces : tuple of PiecePlace
        One per piece, in piece order.
    """

    sheet: tuple[float, float]
    margin: float
    face_size: float
    sheets: int
    pieces: tuple[PiecePlace, ...]

    def suits(self, options: DrawingOptions) -> bool:
        """Whether it was made for the sheet, margin and face size of ``options`` (any face size when unset)."""
        return (max(abs(a - b) for a, b in zip(self.sheet, options.sheet_size)) <= 1e-3
                and abs(self.margin - float(options.margin)) <= TOLERANCE
                and (options.pitch is None or abs(self.face_size - float(options.pitch)) <= TOLERANCE))

    def to_dict(self) -> dict[str, Any]:
        """The contract's JSON form (mm, rounded to 1e-6 mm so it reads back on the same grid)."""
        return {
            "sheet": [_mm(self.sheet[0]), _mm(self.sheet[1])], "margin": _mm(self.margin),
            "face_size": _mm(self.face_size), "sheets": self.sheets,
            "pieces": [{"piece": p.piece, "sheet": p.sheet, "x": _mm(p.x), "y": _mm(p.y), "turns": p.turns,
                        "mirror": p.mirror} for p in self.pieces],
        }

    @classmethod
    def from_dict(cls, data: Any) -> Placement:
        """Read the JSON form, checking every field (one-line :class:`PlacementError` otherwise)."""
        if not isinstance(data, dict):
            raise PlacementError("placement: expected an object with sheet, margin, face_size, sheets, pieces")
        sheet = data.get("sheet")
        if not isinstance(sheet, (list, tuple)) or len(sheet) != 2:
            raise PlacementError("placement.sheet: expected [width, height] in mm")
        w, h = (_number(v, "placement.sheet", positive=True) for v in sheet)
        margin = _number(data.get("margin"), "placement.margin")
        face = _number(data.get("face_size"), "placement.face_size", positive=True)
        sheets = _whole(data.get("sheets"), "placement.sheets", 1, 1000)
        raw = data.get("pieces")
        if not isinstance(raw, list) or not raw:
            raise PlacementError("placement.pieces: expected a list with one entry per piece")
        places = []
        for i, p in enumerate(raw):
            where = f"placement.pieces[{i}]"
            if not isinstance(p, dict):
                raise PlacementError(f"{where}: expected an object with piece, sheet, x, y, turns")
            mirror = p.get("mirror", False)
            if not isinstance(mirror, bool):
                raise PlacementError(f"{where}.mirror: expected true or false")
            places.append(PiecePlace(
                piece=_whole(p.get("piece"), f"{where}.piece", 0, len(raw) - 1),
                sheet=_whole(p.get("sheet"), f"{where}.sheet", 0, sheets - 1),
                x=_number(p.get("x"), f"{where}.x"), y=_number(p.get("y"), f"{where}.y"),
                turns=_whole(p.get("turns", 0), f"{where}.turns", 0, 3), mirror=mirror))
        places.sort(key=lambda p: p.piece)
        if [p.piece for p in places] != list(range(len(places))):
            raise PlacementError("placement.pieces: every piece must appear exactly once")
        return cls((w, h), margin, face, sheets, tuple(places))


def _mm(v: float) -> float:
    return round(float(v), 6)


def _number(v: Any, where: str, *, positive: bool = False) -> float:
    from voxfab._shared.options import quote
    from voxfab._shared.validate import finite_number

    x = finite_number(v)  # 10**400 or Infinity: no number, not an OverflowError
    if x is None:
        raise PlacementError(f"{where}: expected a number, got {quote(v, 40)}")
    if positive and not x > 0:
        raise PlacementError(f"{where}: expected a positive number, got {quote(v, 40)}")
    return x


def _whole(v: Any, where: str, lo: int, hi: int) -> int:
    from voxfab._shared.options import quote
    from voxfab._shared.validate import finite_number

    x = finite_number(v)
    if x is None or x != int(x) or not lo <= x <= hi:
        raise PlacementError(f"{where}: expected a whole number from {lo} to {hi}, got {quote(v, 40)}")
    return int(x)


def turned(cells: npt.NDArray[np.int64], turns: int, mirror: bool = False) -> npt.NDArray[np.int64]:
    """``cells`` (..., 2) mirrored (x -> -x) if asked, then turned ``turns`` quarter turns counter-clockwise."""
    c = np.asarray(cells, dtype=np.int64)
    if mirror:
        c = np.stack([-c[..., 0], c[..., 1]], axis=-1)
    for _ in range(turns % 4):
        c = np.stack([-c[..., 1], c[..., 0]], axis=-1)
    return c


def placement_of(plan: SheetPlan, pieces: list[npt.NDArray[np.int64]], margin: float) -> Placement:
    """The placement a plan gives the pieces whose own corners (in cells) are ``pieces``.

    ``plan.corners2d`` holds the faces of all pieces in order; each piece's
    placed corners are its own turned by some quarter turns and moved by whole
    cells, which this finds back.  ``margin`` is the sheets' margin, mm.
    """
    places = []
    start = 0
    face_origin = plan.face_origin()  # the sheet's origin plus the packer's shift of the face, mm
    for i, own in enumerate(pieces):
        own = np.asarray(own, dtype=np.int64)
        placed = plan.corners2d[start:start + own.shape[0]]
        sheet = int(plan.face_sheet[start])
        for t in range(4):
            shift = (placed - turned(own, t)).reshape(-1, 2)
            if (shift == shift[0]).all():
                break
        else:  # pragma: no cover - the packer only turns and moves pieces
            raise PlacementError(f"piece {i + 1}: its place on the sheet is not a quarter turn of its net")
        x, y = face_origin[start] + shift[0] * plan.pitch
        places.append(PiecePlace(i, sheet, _mm(x), _mm(y), t, False))
        start += own.shape[0]
    return Placement((float(plan.size[0]), float(plan.size[1])), float(margin), float(plan.pitch), plan.count,
                     tuple(places))


def plan_placement(placement: Placement, pieces: list[npt.NDArray[np.int64]], options: DrawingOptions,
                   tab_edges: list[npt.NDArray[np.int64]] | None = None
                   ) -> tuple[SheetPlan, list[npt.NDArray[np.int64]]]:
    """The sheet plan of a given placement, checked as the packer checks its own.

    Each piece is the packer's raster mask (:func:`._sheets.piece_mask`): its
    faces and a band a tab deep beyond each edge of ``tab_edges``.  The masks
    must lie inside the drawable area (a piece alone on its sheet may let its
    tabs reach into the margin, as the packer centres a piece too big for it
    otherwise) and keep the packer's clearance from each other.

    Parameters
    ----------
    placement : Placement
    pieces : list of (n_i, 4, 2) int ndarray
        Each piece's corners in cells, in its own frame.
    options : DrawingOptions
        The drawing's sheet, margin, tabs and face size (``pitch``; None takes
        the placement's).
    tab_edges : list of (t_i, 2) int ndarray, optional
        Each piece's (face, edge) pairs that take a glue tab.

    Returns
    -------
    plan : SheetPlan
    placed : list of (n_i, 4, 2) int ndarray
        Each piece's corners in the plan's cells (pieces two cells apart).

    Raises
    ------
    PlacementError
        A placement for another sheet, margin, face size or number of pieces; a mirrored
        piece; a piece off the packing raster; a piece across the margin; or two pieces
        on or too close to each other.
    """
    from ._sheets import dilated, paper, piece_mask

    size = options.sheet_size
    if abs(placement.sheet[0] - size[0]) > 1e-3 or abs(placement.sheet[1] - size[1]) > 1e-3:
        raise PlacementError(f"placement: made for a {placement.sheet[0]:g} x {placement.sheet[1]:g} mm sheet, "
                             f"the drawing is on {options.sheet} ({size[0]:g} x {size[1]:g} mm)")
    if abs(placement.margin - float(options.margin)) > TOLERANCE:
        raise PlacementError(f"placement: made for a {placement.margin:g} mm margin, the drawing has "
                             f"{options.margin:g} mm")
    pitch = placement.face_size if options.pitch is None else float(options.pitch)
    if abs(pitch - placement.face_size) > TOLERANCE:
        raise PlacementError(f"placement: made for {placement.face_size:g} mm faces, the drawing has {pitch:g} mm")
    if len(placement.pieces) != len(pieces):
        raise PlacementError(f"placement: {len(placement.pieces)} pieces placed, the net has {len(pieces)}")
    if tab_edges is None:
        tab_edges = [np.zeros((0, 2), dtype=np.int64) for _ in pieces]
    used = sorted({p.sheet for p in placement.pieces})
    renumber = {s: k for k, s in enumerate(used)}  # an emptied sheet is dropped, not printed blank
    alone = {s: sum(p.sheet == s for p in placement.pieces) == 1 for s in used}
    sheet_paper = paper(options, pitch)
    x0, y0, x1, y1 = sheet_paper.area
    step, clear, raster = sheet_paper.step, sheet_paper.clear, sheet_paper.raster
    boards = {s: np.full(raster, -1, dtype=np.int64) for s in used}
    placed, shifts = [], []
    offset = 0
    for place, own, tabs in zip(placement.pieces, pieces, tab_edges):
        name, sheet = f"piece {place.piece + 1}", renumber[place.sheet]
        if place.mirror:
            raise PlacementError(f"{name}: a mirrored piece would fold inside out; place it unmirrored")
        cells = turned(np.asarray(own, dtype=np.int64), place.turns)
        lo = cells.reshape(-1, 2).min(axis=0)
        mask, start = piece_mask(cells, tabs, options, pitch)
        base = np.array([place.x, place.y]) + lo * pitch  # mm of the piece's lowest cell corner
        at = (base - (x0, y0)) / step + start
        # A piece alone on its sheet may sit anywhere (a one-piece net is centred, not packed); pieces
        # that share a sheet stay on the packer's raster, where their clearance is checked.
        if not alone[place.sheet] and np.abs(at - np.rint(at)).max() > 1e-3:
            raise PlacementError(f"{name}: not on the packing grid of {step:.3g} mm; move pieces by whole faces")
        ax, ay = (int(v) for v in np.floor(at + 1e-3))
        inside = ax >= 0 and ay >= 0 and ax + mask.shape[0] <= raster[0] and ay + mask.shape[1] <= raster[1]
        faces_mm = base + (cells - lo).reshape(-1, 2) * pitch
        faces_in = (faces_mm.min(axis=0) >= (x0 - TOLERANCE, y0 - TOLERANCE)).all() and \
            (faces_mm.max(axis=0) <= (x1 + TOLERANCE, y1 + TOLERANCE)).all()
        if not (inside or (alone[place.sheet] and faces_in)):
            raise PlacementError(f"{name} crosses the margin of sheet {sheet + 1}: keep it and its glue tabs "
                                 f"{options.margin:g} mm from the edges")
        board = boards[place.sheet]
        if not alone[place.sheet]:
            # the mask grown by the clearance, clipped to the sheet, against the pieces placed before it
            gx0, gy0 = max(ax - clear, 0), max(ay - clear, 0)
            gx1 = min(ax + mask.shape[0] + clear, raster[0])
            gy1 = min(ay + mask.shape[1] + clear, raster[1])
            grown = dilated(mask, clear)[gx0 - ax + clear:gx1 - ax + clear, gy0 - ay + clear:gy1 - ay + clear]
            hit = board[gx0:gx1, gy0:gy1][grown]
            hit = hit[hit >= 0]
            if hit.size:
                a, b = sorted((int(hit[0]), place.piece))
                raise PlacementError(f"pieces {a + 1} and {b + 1} overlap or touch on sheet {sheet + 1}: leave "
                                     "paper between them for the glue tabs")
            board[ax:ax + mask.shape[0], ay:ay + mask.shape[1]][mask] = place.piece
        local = cells - lo + (offset, 0)
        placed.append(local)
        shifts.append(np.repeat([base - (offset * pitch, 0.0)], own.shape[0], axis=0))
        offset = int(local[..., 0].max()) + 2  # the next piece two cells past this one
    face_sheet = np.concatenate([np.full(c.shape[0], renumber[p.sheet], dtype=np.int64)
                                 for p, c in zip(placement.pieces, placed)])
    single = len(pieces) == 1 and placement.pieces[0].turns % 2 == 1
    plan = SheetPlan(pitch, single, np.concatenate(placed), face_sheet, np.zeros((len(used), 2)),
                     (x0, y0, x1, y1), size, np.concatenate(shifts))
    return plan, placed
