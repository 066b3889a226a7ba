"""Joints between consecutive layers and the dowel holes that register them.

A *joint* is the area shared by a piece of layer ``k`` and a piece of layer
``k + 1`` (its cells are filled in both layers).  Dowels are placed inside a
joint, at the pole of inaccessibility of the joint minus the holes already
drilled, so each dowel is as far from every edge as the joint allows.  A
dowel goes through every plate of both layers, so its holes line up.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

from ._outline import cells_outline, scaled


@dataclasses.dataclass(frozen=True)
class Dowel:
    """One dowel through the plates of two consecutive layers.

    Attributes
    ----------
    x, y : float
        Centre in mm in the stack's ``(u, v)`` frame.
    lower, upper : str
        The pieces it joins, as ``"layer-piece"`` ids (``upper`` is one layer up).
    clearance : float
        Distance in mm from the hole's edge to the nearest edge of the joint or
        to another hole.
    """

    x: float
    y: float
    lower: str
    upper: str
    clearance: float


@dataclasses.dataclass(frozen=True, eq=False)
class Joint:
    """Cells shared by piece ``lower`` of layer ``k`` and piece ``upper`` of layer ``k + 1``."""

    lower: str
    upper: str
    cells: npt.NDArray[np.int64]


def find_joints(labels: npt.NDArray[np.int32]) -> tuple[Joint, ...]:
    """All joints of a labelled stack, bottom up, by (lower, upper) piece number.

    Parameters
    ----------
    labels : (L, U, V) int ndarray
        Piece labels per layer, as from :func:`slice_stack`.
    """
    out = []
    for k in range(labels.shape[0] - 1):
        a, b = labels[k], labels[k + 1]
        both = (a > 0) & (b > 0)
        if not both.any():
            continue
        uv = np.argwhere(both).astype(np.int64)
        pa = a[both].astype(np.int64)
        pb = b[both].astype(np.int64)
        order = np.lexsort((pb, pa))
        pa, pb, uv = pa[order], pb[order], uv[order]
        cut = np.flatnonzero((np.diff(pa) != 0) | (np.diff(pb) != 0)) + 1
        for lo, hi in zip(np.r_[0, cut], np.r_[cut, len(pa)]):
            out.append(Joint(f"{k + 1}-{pa[lo]}", f"{k + 2}-{pb[lo]}", uv[lo:hi]))
    return tuple(out)


def _clearance(point: npt.NDArray[np.float64], joint: object, existing: npt.NDArray[np.float64], radius: float) -> float:
    """Exact distance from a hole of ``radius`` at ``point`` to the joint edge or other holes."""
    import shapely

    d = float(shapely.distance(joint.boundary, shapely.Point(point))) - radius
    if not shapely.contains_xy(joint, *point):
        return -np.inf
    if len(existing):
        d = min(d, float(np.min(np.hypot(*(existing - point).T))) - 2.0 * radius)
    return d


def _best_point(
    joint: object, existing: npt.NDArray[np.float64], radius: float, tolerance: float
) -> tuple[npt.NDArray[np.float64], float] | None:
    """Centre of the best new hole in ``joint`` and its clearance, or None if none fits."""
    import shapely
    from shapely.ops import polylabel

    region = joint
    if len(existing):
        # only holes near the joint can cut it
        x0, y0, x1, y1 = joint.bounds
        near = (existing[:, 0] > x0 - radius) & (existing[:, 0] < x1 + radius)
        near &= (existing[:, 1] > y0 - radius) & (existing[:, 1] < y1 + radius)
        existing = existing[near]
    if len(existing):
        discs = shapely.buffer(shapely.multipoints(existing), radius, quad_segs=8)
        region = shapely.difference(joint, discs)
    best: tuple[npt.NDArray[np.float64], float] | None = None
    for part in getattr(region, "geoms", [region]):
        if part.is_empty or part.geom_type != "Polygon":
            continue
        c = polylabel(part, tolerance=tolerance)
        p = np.round(np.array([c.x, c.y]), 3)
        d = _clearance(p, joint, existing, radius)
        if best is None or d > best[1]:
            best = (p, d)
    return best


def place_dowels(
    labels: npt.NDArray[np.int32],
    *,
    pitch: float,
    diameter: float,
    margin: float,
    per_joint: int = 2,
) -> tuple[tuple[Dowel, ...], tuple[Joint, ...]]:
    """Place dowel holes in every joint where they fit.

    Parameters
    ----------
    labels : (L, U, V) int ndarray
        Piece labels per layer.
    pitch : float
        Voxel pitch in mm.
    diameter : float
        Dowel hole diameter in mm.
    margin : float
        Least material in mm between a hole and any plate edge or other hole.
    per_joint : int
        Most dowels per joint; a second one stops plates turning about the first.

    Returns
    -------
    dowels : tuple of Dowel
        Bottom up, joint by joint.
    joints : tuple of Joint
    """
    radius = diameter / 2.0
    need_cells = 2.0 * (radius + margin) / pitch
    joints = find_joints(labels)
    holes: dict[int, list[npt.NDArray[np.float64]]] = {}
    dowels = []
    for j in joints:
        k = int(j.lower.split("-")[0])
        # a joint narrower than a hole plus its margins cannot take one (cheap test first)
        if np.ptp(j.cells[:, 0]) + 1 < need_cells or np.ptp(j.cells[:, 1]) + 1 < need_cells:
            continue
        region = scaled(cells_outline(j.cells), pitch)
        for _ in range(per_joint):
            near = holes.get(k, []) + holes.get(k + 1, [])
            existing = np.array(near, dtype=np.float64).reshape(-1, 2)
            found = _best_point(region, existing, radius, 0.05 * pitch)
            if found is None or found[1] < margin - 1e-9:
                break
            p, d = found
            dowels.append(Dowel(float(p[0]), float(p[1]), j.lower, j.upper, round(d, 6)))
            holes.setdefault(k, []).append(p)
            holes.setdefault(k + 1, []).append(p)
    return tuple(dowels), joints
