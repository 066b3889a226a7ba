"""Nesting plates onto sheets: part in part, then bounding boxes packed by rectpack.

Small plates first go into the voxel holes of bigger ones; the rest are
packed by their bounding boxes, turned by 90° where that packs better.
Kerf compensation happens here, because it only concerns the cutting paths:
outlines grow by ``kerf / 2`` (mitred, so they stay rectilinear), voxel holes
and dowel holes shrink by the same amount.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import check_positive
from voxfab.drawing import parse_sheet
from voxfab.errors import FabricationError, InvalidShapeError

from ._stack import Plate

#: rectpack works on integers: lengths are rounded up to this many mm.
_QUANTUM = 0.01


@dataclasses.dataclass(frozen=True, eq=False)
class PlacedPart:
    """A plate placed on a sheet, with its cutting paths in sheet mm.

    Attributes
    ----------
    plate : Plate
    turns : int
        Quarter turns counter-clockwise (0-3) applied before moving.
    offset : (2,) float ndarray
        Translation applied after the turn.
    host : int
        Number of the plate in whose voxel hole this one is nested, or 0.
    cut : tuple of (n, 2) float ndarray
        Closed rings (first point repeated): outline, then voxel holes, kerf-compensated.
    circles : (H, 3) float ndarray
        Dowel holes as ``x, y, radius`` (kerf-compensated).
    score : tuple of (n, 2) float ndarray
    engrave : tuple of (n, 2) float ndarray
    """

    plate: Plate
    turns: int
    offset: npt.NDArray[np.float64]
    host: int
    cut: tuple[npt.NDArray[np.float64], ...]
    circles: npt.NDArray[np.float64]
    score: tuple[npt.NDArray[np.float64], ...]
    engrave: tuple[npt.NDArray[np.float64], ...]

    @property
    def rotated(self) -> bool:
        """Whether the plate is turned on the sheet."""
        return self.turns % 4 != 0

    def place(self, xy: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Map ``(n, 2)`` plate coordinates (mm) to sheet coordinates."""
        return _transform(np.asarray(xy, dtype=np.float64).reshape(-1, 2), self.turns, self.offset)

    def polygon(self) -> object:
        """The placed part (cut outline minus dowel holes) as a shapely Polygon."""
        import shapely

        shell, *holes = self.cut
        body = shapely.Polygon(shell, holes)
        if len(self.circles):
            pts = shapely.points(self.circles[:, :2])
            discs = shapely.buffer(pts, self.circles[:, 2], quad_segs=16)
            body = shapely.difference(body, shapely.union_all(discs))
        return body


@dataclasses.dataclass(frozen=True, eq=False)
class PlateSheet:
    """One sheet of material with the parts nested on it.

    Attributes
    ----------
    index : int
        1-based sheet number.
    width, height : float
        Sheet size in mm.
    parts : tuple of PlacedPart
        By plate number.
    colour : str
        ``"#rrggbb"`` of the material when the plates are nested by colour, else ``""``.
    """

    index: int
    width: float
    height: float
    parts: tuple[PlacedPart, ...]
    colour: str = ""

    @property
    def material_area(self) -> float:
        """Area in mm² of the plates on this sheet (exact dowel circles, no kerf)."""
        return float(sum(p.plate.area for p in self.parts))


def _turn(xy: npt.NDArray[np.float64], turns: int) -> npt.NDArray[np.float64]:
    """Rotate points by ``turns`` quarter turns counter-clockwise: (x, y) → (−y, x)."""
    for _ in range(turns % 4):
        xy = np.column_stack([-xy[:, 1], xy[:, 0]])
    return xy


def _transform(xy: npt.NDArray[np.float64], turns: int, offset: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    return _turn(xy, turns) + offset


def _turned_bounds(bounds: tuple[float, float, float, float], turns: int) -> npt.NDArray[np.float64]:
    x0, y0, x1, y1 = bounds
    corners = _turn(np.array([[x0, y0], [x1, y1]], dtype=np.float64), turns)
    return np.concatenate([corners.min(axis=0), corners.max(axis=0)])


def _erode_by_box(region: object, width: float, height: float) -> object:
    """Centres of ``width × height`` boxes inside a rectilinear ``region`` (exact).

    Stretching x by ``height / width`` turns the box into a square, and a mitred
    inward offset of a rectilinear polygon is exactly its erosion by a square.
    """
    import shapely

    sx = height / width
    squeezed = shapely.transform(region, lambda xy: xy * (sx, 1.0))
    core = squeezed.buffer(-height / 2.0, join_style="mitre")
    return shapely.transform(core, lambda xy: xy * (1.0 / sx, 1.0))


def _nest_in_holes(shapes: list[object], spacing: float) -> dict[int, tuple[int, int, npt.NDArray[np.float64]]]:
    """Put small plates inside the voxel holes of larger ones (one level deep).

    Guests are placed by their bounding boxes at the lowest, then leftmost,
    free spot of a hole shrunk by ``spacing``; bigger guests first.

    Returns
    -------
    guests : dict
        Guest index → (host index, quarter turns, offset in the host's frame).
    """
    import shapely

    order = sorted(range(len(shapes)), key=lambda i: (-shapes[i].area, i))
    placed: dict[int, tuple[int, int, npt.NDArray[np.float64]]] = {}
    hosts: set[int] = set()
    for host in order:
        if host in placed or not shapes[host].interiors:
            continue
        for ring in shapes[host].interiors:
            free = shapely.Polygon(ring).buffer(-spacing, join_style="mitre")
            for guest in order:
                if free.is_empty:
                    break
                if guest == host or guest in placed or guest in hosts or shapes[guest].area >= free.area:
                    continue
                for turns in (0, 1):
                    gx0, gy0, gx1, gy1 = _turned_bounds(shapes[guest].bounds, turns)
                    gw, gh = gx1 - gx0, gy1 - gy0
                    fx0, fy0, fx1, fy1 = free.bounds
                    if gw > fx1 - fx0 or gh > fy1 - fy0:
                        continue
                    core = _erode_by_box(free, gw, gh)
                    if core.is_empty:
                        continue
                    pts = shapely.get_coordinates(core)
                    best = np.lexsort((pts[:, 0], pts[:, 1]))[0]  # lowest, then leftmost
                    cx, cy = pts[best]
                    lo = np.array([cx - gw / 2.0, cy - gh / 2.0])
                    placed[guest] = (host, turns, lo - (gx0, gy0))
                    hosts.add(host)
                    box = shapely.box(lo[0], lo[1], lo[0] + gw, lo[1] + gh)
                    free = free.difference(box.buffer(spacing, join_style="mitre"))
                    break
    return placed


def _compensated(plate: Plate, kerf: float) -> object:
    if kerf <= 0:
        return plate.outline
    import shapely

    return shapely.orient_polygons(plate.outline.buffer(kerf / 2.0, join_style="mitre"))


def _units(length: float) -> int:
    return int(math.ceil(round(length / _QUANTUM, 6)))


def nest_plates(
    plates: tuple[Plate, ...] | list[Plate],
    *,
    sheet: tuple[float, float] | str = (600.0, 400.0),
    margin: float = 5.0,
    spacing: float = 2.0,
    kerf: float = 0.0,
    in_holes: bool = True,
) -> tuple[PlateSheet, ...]:
    """Nest plates onto as few sheets as the packer finds.

    Small plates first go inside the voxel holes of bigger ones (part in
    part); the remaining plates, each carrying its guests, are packed by their
    bounding boxes with rectpack, turned by 90° where that packs better.

    Parameters
    ----------
    plates : sequence of Plate
    sheet : (float, float) or str
        Sheet width and height in mm, or ``"WxH"``.
    margin : float
        Empty border in mm along the sheet edges.
    spacing : float
        Least gap in mm between parts (between kerf-compensated outlines).
    kerf : float
        Laser kerf in mm; outlines grow and holes shrink by ``kerf / 2``.
    in_holes : bool
        Nest small plates inside the voxel holes of larger ones.

    Returns
    -------
    sheets : tuple of PlateSheet

    Raises
    ------
    FabricationError
        When a plate does not fit the sheet inside its margin, in either orientation.
    """
    from rectpack import SORT_AREA, MaxRectsBssf, PackingBin, PackingMode, newPacker

    w, h = parse_sheet(sheet) if isinstance(sheet, str) else (check_positive(sheet[0], name="sheet width"), check_positive(sheet[1], name="sheet height"))
    for value, name in ((margin, "margin"), (spacing, "spacing"), (kerf, "kerf")):
        if not np.isfinite(value) or value < 0:
            raise InvalidShapeError(f"{name}: expected a number >= 0, got {value!r}")
    bin_w, bin_h = _units(w - 2 * margin + spacing), _units(h - 2 * margin + spacing)
    if w - 2 * margin <= 0 or h - 2 * margin <= 0:
        raise InvalidShapeError(f"margin: {margin} mm leaves no room on a {w:g}x{h:g} mm sheet")
    if any(0 < p.hole_diameter <= kerf for p in plates):
        raise InvalidShapeError(f"kerf: {kerf} mm is not smaller than the dowel hole diameter")
    shapes = [_compensated(p, kerf) for p in plates]
    guests = _nest_in_holes(shapes, spacing) if in_holes else {}
    packer = newPacker(
        mode=PackingMode.Offline, bin_algo=PackingBin.BFF, pack_algo=MaxRectsBssf,
        sort_algo=SORT_AREA, rotation=True,
    )
    sizes = {}
    for i, (p, s) in enumerate(zip(plates, shapes)):
        x0, y0, x1, y1 = s.bounds
        rw, rh = _units(x1 - x0 + spacing), _units(y1 - y0 + spacing)
        if not ((rw <= bin_w and rh <= bin_h) or (rh <= bin_w and rw <= bin_h)):
            raise FabricationError(
                f"plate {p.id} ({x1 - x0:.1f}x{y1 - y0:.1f} mm) does not fit a {w:g}x{h:g} mm "
                f"sheet with a {margin:g} mm margin"
            )
        if i not in guests:
            sizes[i] = (rw, rh)
            packer.add_rect(rw, rh, rid=i)
    packer.add_bin(bin_w, bin_h, count=float("inf"))
    packer.pack()
    moves: dict[int, tuple[int, int, npt.NDArray[np.float64], int]] = {}  # index → bin, turns, offset, host
    for b, x, y, rw, rh, i in packer.rect_list():
        turns = int((rw, rh) != sizes[i])
        lo = _turned_bounds(shapes[i].bounds, turns)[:2]
        moves[i] = (b, turns, np.array([margin + x * _QUANTUM, margin + y * _QUANTUM]) - lo, 0)
    for g, (host, turns, rel) in sorted(guests.items()):
        b, host_turns, host_offset, _ = moves[host]
        # the guest moves with its host: turn and offset compose
        moves[g] = (b, (turns + host_turns) % 4, _turn(rel[None, :], host_turns)[0] + host_offset, plates[host].number)
    by_bin: dict[int, list[PlacedPart]] = {}
    for i, (b, turns, offset, host_number) in moves.items():
        p, s = plates[i], shapes[i]
        rings = [np.asarray(s.exterior.coords)] + [np.asarray(r.coords) for r in s.interiors]
        radius = p.hole_diameter / 2.0 - kerf / 2.0
        circles = (
            np.column_stack([_transform(p.holes, turns, offset), np.full(len(p.holes), radius)])
            if len(p.holes) else np.zeros((0, 3))
        )
        by_bin.setdefault(b, []).append(
            PlacedPart(
                plate=p,
                turns=turns,
                offset=offset,
                host=host_number,
                cut=tuple(_transform(r, turns, offset) for r in rings),
                circles=circles,
                score=tuple(_transform(a, turns, offset) for a in p.score),
                engrave=tuple(_transform(a, turns, offset) for a in p.label.strokes),
            )
        )
    return tuple(
        PlateSheet(index=k + 1, width=w, height=h, parts=tuple(sorted(by_bin[b], key=lambda q: q.plate.number)))
        for k, b in enumerate(sorted(by_bin))
    )
