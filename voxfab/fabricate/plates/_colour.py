"""The colour of each plate: the colour covering most of its section, and nesting by colour.

A plate lies in the voxel solid; its mid-plane crosses voxels, and each part of
the plate takes the colour of the voxel its mid-plane point is in.  The plate's
frame ``(u, v)`` is split where the mid-plane crosses a voxel boundary, so each
box of the split lies in one voxel; the box's area inside the plate (dowel holes
and slots removed) is that voxel's weight.  This is exact for every style: the
stacked and interlocked planes follow the voxel lattice, a radial plane is
vertical, so its boxes are a voxel layer high and as wide as its line stays in
one voxel column.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import numpy.typing as npt

from voxfab.shape import VoxelColours, crop, fill_cavities

from ._nest import PlateSheet, nest_plates
from ._outline import _TRANSPOSE, axis_value
from ._stack import Plate


@dataclasses.dataclass(frozen=True)
class PlateColour:
    """The main colour of one plate.

    Attributes
    ----------
    hex : str
        ``"#rrggbb"`` of the colour covering most of the plate's area.
    share : float
        Its fraction of the plate's area (0..1].
    areas : tuple of (str, float)
        Area in mm² of each colour on the plate, largest first.
    """

    hex: str
    share: float
    areas: tuple[tuple[str, float], ...]

    def to_json(self) -> dict[str, object]:
        return {"hex": self.hex, "share": round(self.share, 4) + 0.0}


def _breaks(origin: npt.NDArray[np.float64], direction: npt.NDArray[np.float64], lo: float, hi: float,
            pitch: float) -> npt.NDArray[np.float64]:
    """Parameters ``t`` in ``lo..hi`` where ``origin + t·direction`` crosses a voxel boundary, with the ends."""
    ts = [np.array([lo, hi])]
    for a in range(3):
        d = direction[a]
        if abs(d) < 1e-12:
            continue
        m0, m1 = sorted(((origin[a] + lo * d) / pitch, (origin[a] + hi * d) / pitch))
        m = np.arange(math.ceil(m0), math.floor(m1) + 1, dtype=np.float64)
        ts.append((m * pitch - origin[a]) / d)
    return np.unique(np.clip(np.concatenate(ts), lo, hi))


def section_areas(polygon: object, origin: npt.ArrayLike, u_dir: npt.ArrayLike, v_dir: npt.ArrayLike,
                  index: npt.NDArray[np.uint8], pitch: float) -> dict[int, float]:
    """Area in mm² of a plate's ``polygon`` (its frame, mm) over each colour index of the voxels it crosses.

    ``origin + u·u_dir + v·v_dir`` is the mid-plane point of ``(u, v)`` in the
    frame of ``index`` (voxel ``i`` spans ``i·pitch..(i + 1)·pitch``).
    """
    import shapely

    o, u, v = (np.asarray(a, dtype=np.float64) for a in (origin, u_dir, v_dir))
    x0, y0, x1, y1 = polygon.bounds
    us, vs = _breaks(o, u, x0, x1, pitch), _breaks(o, v, y0, y1, pitch)
    a0, b0 = np.meshgrid(us[:-1], vs[:-1], indexing="ij")
    a1, b1 = np.meshgrid(us[1:], vs[1:], indexing="ij")
    boxes = shapely.box(a0.ravel(), b0.ravel(), a1.ravel(), b1.ravel())
    areas = shapely.area(shapely.intersection(boxes, polygon))
    keep = areas > 1e-9 * pitch * pitch
    mid_u = ((a0 + a1) / 2).ravel()[keep]
    mid_v = ((b0 + b1) / 2).ravel()[keep]
    points = o + mid_u[:, None] * u + mid_v[:, None] * v
    cells = np.clip(np.floor(points / pitch).astype(np.intp), 0, np.array(index.shape) - 1)
    found = index[cells[:, 0], cells[:, 1], cells[:, 2]]
    out: dict[int, float] = {}
    for i, a in zip(found.tolist(), areas[keep].tolist()):
        if i:
            out[i] = out.get(i, 0.0) + a
    return out


def main_colour(areas: dict[int, float], colours: VoxelColours) -> PlateColour | None:
    """The colour with most area (indices of one RGB count together; ties go to the lower hex)."""
    by_hex: dict[str, float] = {}
    for i, a in areas.items():
        h = colours.hex(i)
        by_hex[h] = by_hex.get(h, 0.0) + a
    total = sum(by_hex.values())
    if total <= 0:
        return None
    ranked = sorted(by_hex.items(), key=lambda kv: (-kv[1], kv[0]))
    return PlateColour(ranked[0][0], ranked[0][1] / total, tuple(ranked))


def stack_colours(stack: object, colours: VoxelColours) -> tuple[PlateColour | None, ...]:
    """The main colour of each plate of a stacked construction, in plate order."""
    ax = axis_value(stack.axis)
    w, u, v = _TRANSPOSE[ax]
    index = crop(colours.index)
    pitch = stack.pitch
    unit = np.eye(3)
    seen: dict[tuple[int, int], PlateColour | None] = {}
    out = []
    for p in stack.plates:
        key = (p.layer, p.piece)
        if key not in seen:  # the copies of a piece share its section
            origin = unit[w] * (stack.sources[p.layer - 1] - 0.5) * pitch
            seen[key] = main_colour(section_areas(p.polygon(), origin, unit[u], unit[v], index, pitch), colours)
        out.append(seen[key])
    return tuple(out)


def construction_colours(construction: object, colours: VoxelColours) -> tuple[PlateColour | None, ...]:
    """The main colour of each plate of a slotted construction, in plate order.

    The plates run through the shape's closed cavities (:func:`~._slotted.solid_grid`):
    there a plate takes the colour of the nearest voxel.
    """
    grid = colours.index != 0
    index = crop(colours.fitted(fill_cavities(grid)).index)
    return tuple(main_colour(section_areas(p.outline, p.origin, p.u_dir, p.v_dir, index, construction.pitch),
                             colours) for p in construction.plates)


def nest_by_colour(plates: tuple[Plate, ...], plate_colours: tuple[PlateColour | None, ...],
                   **nest: object) -> tuple[PlateSheet, ...]:
    """Nest the plates of each main colour on sheets of their own, each sheet naming its colour.

    Colours come in the order of their first plate; sheets are numbered on through the colours.
    """
    groups: dict[str, list[Plate]] = {}
    for p, c in zip(plates, plate_colours):
        groups.setdefault(c.hex if c is not None else "", []).append(p)
    sheets: list[PlateSheet] = []
    for hex_, group in groups.items():
        for s in nest_plates(tuple(group), **nest):
            sheets.append(dataclasses.replace(s, index=len(sheets) + 1, colour=hex_))
    return tuple(sheets)
