"""Voxels that touch only along an edge or only at a corner, and bridges across them.

Two filled voxels that share an edge while both voxels beside that edge are
empty print as two pieces held by a hair; so do two voxels that are the only
filled cells of a 2×2×2 block and touch at its centre.  Every other zero-width
junction of solids is one of these two (two pieces meeting at a point either
contain an edge-touching pair, or are exactly the two opposite cells).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import as_grid

#: The six edge diagonals (i, j, sign of j) up to reversal: voxel v touches v + e_i + s·e_j.
_EDGE_DIAGONALS = [(i, j, s) for i in range(3) for j in range(i + 1, 3) for s in (1, -1)]
#: The four body diagonals of a 2×2×2 block as (start corner, opposite corner).
_BODY_DIAGONALS = [((0, 0, 0), (1, 1, 1)), ((1, 0, 0), (0, 1, 1)), ((0, 1, 0), (1, 0, 1)), ((0, 0, 1), (1, 1, 0))]


@dataclasses.dataclass(frozen=True)
class Contacts:
    """Zero-width junctions of a voxel grid, in voxel-corner coordinates.

    Attributes
    ----------
    edges : (E, 2, 3) int64 ndarray
        The two end points of each contact edge (unit length, sorted).
    edge_voxels : (E, 2, 3) int64 ndarray
        The two voxels touching along each edge.
    points : (K, 3) int64 ndarray
        The point of each corner-only contact.
    point_voxels : (K, 2, 3) int64 ndarray
        The two voxels touching there.
    """

    edges: npt.NDArray[np.int64]
    edge_voxels: npt.NDArray[np.int64]
    points: npt.NDArray[np.int64]
    point_voxels: npt.NDArray[np.int64]

    @property
    def count(self) -> int:
        """Total number of contacts."""
        return int(self.edges.shape[0] + self.points.shape[0])

    def describe(self, limit: int = 8) -> str:
        """One line listing the contacts by voxel pairs (the first ``limit``)."""

        def fmt(v: npt.NDArray[np.int64]) -> str:
            return "(" + ",".join(str(int(c)) for c in v) + ")"

        items = [f"edge {fmt(a)}-{fmt(b)}" for a, b in self.edge_voxels]
        items += [f"corner {fmt(a)}-{fmt(b)}" for a, b in self.point_voxels]
        more = f" and {len(items) - limit} more" if len(items) > limit else ""
        return (
            f"{self.edges.shape[0]} edge-only and {self.points.shape[0]} corner-only contacts "
            f"between voxels: {', '.join(items[:limit])}{more}"
        )


#: No contacts at all: what a bridged grid promises.
NO_CONTACTS = Contacts(
    edges=np.zeros((0, 2, 3), dtype=np.int64),
    edge_voxels=np.zeros((0, 2, 3), dtype=np.int64),
    points=np.zeros((0, 3), dtype=np.int64),
    point_voxels=np.zeros((0, 2, 3), dtype=np.int64),
)


def find_contacts(grid: npt.ArrayLike) -> Contacts:
    """Find voxel pairs that touch only along an edge or only at a corner.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The shape.

    Returns
    -------
    Contacts
        Sorted by voxel, so the result is deterministic.
    """
    from ._contact_scan import contact_scan

    g = as_grid(grid, allow_empty=True)
    p = np.pad(g, 1)
    # Both voxels of a contact have an empty face neighbour (the cells beside the
    # contact), so only surface voxels are looked at.
    inner = p[2:, 1:-1, 1:-1] & p[:-2, 1:-1, 1:-1]
    inner &= p[1:-1, 2:, 1:-1]
    inner &= p[1:-1, :-2, 1:-1]
    inner &= p[1:-1, 1:-1, 2:]
    inner &= p[1:-1, 1:-1, :-2]
    q = np.argwhere(g & ~inner) + 1  # padded coordinates, sorted
    e, ev, pt, pv = contact_scan(
        p, q.astype(np.int64), np.array(_EDGE_DIAGONALS, dtype=np.int64), np.array(_BODY_DIAGONALS, dtype=np.int64)
    )
    eo = np.argsort(_pair_keys(ev), kind="stable")
    po = np.argsort(_pair_keys(pv), kind="stable")
    return Contacts(edges=e[eo], edge_voxels=ev[eo], points=pt[po], point_voxels=pv[po])


def _pair_keys(pairs: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    """One int64 per voxel pair ``(P, 2, 3)`` ordered like the six coordinates lexicographically.

    Coordinates are in ``-1..256`` (at most 256 voxels a side), so base 260 keeps
    the six digits apart and 260**6 < 2**63.
    """
    key = np.zeros(pairs.shape[0], dtype=np.int64)
    for c in pairs.reshape(-1, 6).T:
        key = key * 260 + (c + 1)
    return key


def bridge_boxes(contacts: Contacts, *, pitch: float, width: float) -> npt.NDArray[np.float64]:
    """Boxes that join each contact, as ``(B, 2, 3)`` min and max corners in mm.

    Collinear contact edges in a row become one box.  An edge box is ``width``
    square across the edge and runs the length of the row (``width / 2`` further
    where another contact shares the end); a corner box is a cube of side
    ``width`` centred on the point.
    """
    boxes = []
    e = contacts.edges
    if e.shape[0]:
        axis = np.argmax(e[:, 1] - e[:, 0], axis=1)
        # Row key: axis, the two fixed coordinates, and which diagonal (the voxel pair's offset).
        off = contacts.edge_voxels[:, 1] - contacts.edge_voxels[:, 0]
        fixed = np.where(np.arange(3)[None, :] == axis[:, None], 0, e[:, 0])
        along = e[np.arange(e.shape[0]), 0, axis]
        cols = [along, *off.T[::-1], *fixed.T[::-1], axis]
        order = np.lexsort(cols)
        key = np.column_stack([axis, fixed, off])[order]
        al = along[order]
        brk = np.ones(order.size, dtype=bool)
        brk[1:] = (key[1:] != key[:-1]).any(axis=1) | (al[1:] != al[:-1] + 1)
        run = np.cumsum(brk) - 1
        n_runs = int(run[-1]) + 1
        r_lo = np.full(n_runs, np.iinfo(np.int64).max)
        r_hi = np.zeros(n_runs, dtype=np.int64)
        np.minimum.at(r_lo, run, al)
        np.maximum.at(r_hi, run, al + 1)
        first = np.flatnonzero(brk)
        r_axis = key[first, 0]
        centre = key[first, 1:4].astype(np.float64) * pitch
        lo = centre - width / 2.0
        hi = centre + width / 2.0
        rows = np.arange(n_runs)
        # Where a row ends at a point another contact also uses, the box reaches
        # width/2 past it so the boxes meeting there leave no closed pocket;
        # elsewhere it ends with the row, so no stretch of the contact is left pinched.
        end_lo = np.zeros((n_runs, 3), dtype=np.int64)
        end_hi = np.zeros((n_runs, 3), dtype=np.int64)
        end_lo[:] = key[first, 1:4]
        end_hi[:] = key[first, 1:4]
        end_lo[rows, r_axis] = r_lo
        end_hi[rows, r_axis] = r_hi
        shared = _shared_points(np.concatenate([end_lo, end_hi]), e, contacts.points)
        ext_lo, ext_hi = shared[:n_runs], shared[n_runs:]
        lo[rows, r_axis] = r_lo * pitch - np.where(ext_lo, width / 2.0, 0.0)
        hi[rows, r_axis] = r_hi * pitch + np.where(ext_hi, width / 2.0, 0.0)
        boxes.append(np.stack([lo, hi], axis=1))
    if contacts.points.shape[0]:
        c = contacts.points.astype(np.float64) * pitch
        boxes.append(np.stack([c - width / 2.0, c + width / 2.0], axis=1))
    return np.concatenate(boxes) if boxes else np.zeros((0, 2, 3))


def _shared_points(
    ends: npt.NDArray[np.int64], edges: npt.NDArray[np.int64], points: npt.NDArray[np.int64]
) -> npt.NDArray[np.bool_]:
    """Whether each row end is used by more than that row: by two contact edges or a corner contact."""
    all_pts = np.concatenate([edges[:, 0], edges[:, 1], points, points]) if len(points) else np.concatenate(
        [edges[:, 0], edges[:, 1]]
    )
    # Scalar keys (one-to-one and order-preserving) are much faster to unique than rows.
    keys, counts = np.unique(_row_keys(all_pts), return_counts=True)
    # An end inside a row is used by two edges of the same row; a row end by one unless shared.
    end_keys = _row_keys(ends)
    idx = np.searchsorted(keys, end_keys)
    idx = np.minimum(idx, len(keys) - 1)
    hit = keys[idx] == end_keys
    return hit & (counts[idx] >= 2)


def _row_keys(pts: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    """Order-preserving scalar keys of lattice points (lexicographic like ``np.unique(axis=0)``)."""
    q = pts.astype(np.int64) + 1
    return (q[:, 0] * 1024 + q[:, 1]) * 1024 + q[:, 2]


def bridged_grid(
    grid: npt.NDArray[np.bool_],
    boxes: npt.NDArray[np.float64],
    *,
    pitch: float,
    max_side: int = 256,
    labels: npt.NDArray[np.integer] | None = None,
) -> tuple[npt.NDArray[np.bool_], tuple[npt.NDArray[np.float64], ...]] | tuple[
    npt.NDArray[np.bool_], tuple[npt.NDArray[np.float64], ...], npt.NDArray[np.int64]
] | None:
    """The shape and its bridge boxes as one rectilinear grid, or None when too fine.

    Every box face lies on an extra lattice plane, so shape ∪ boxes is exactly a
    union of cells of the refined grid and can be meshed like voxels, without
    CAD booleans.

    Parameters
    ----------
    labels : int ndarray shaped like ``grid``, optional
        Part of each filled voxel (> 0, e.g. its 26-connected component; ignored
        at empty voxels).  When given, a third array with the part of every cell
        is returned: a cell inside a voxel takes that voxel's part; each bridge
        box, one connected block over voxels of one contact, takes the largest
        part it overlaps.

    Returns
    -------
    cells : bool ndarray
        Filled cells of the refined grid.
    coords : tuple of three 1D float64 arrays
        Plane positions along each axis, in voxels.
    parts : int64 ndarray, only with ``labels``
        Part of each cell, 0 where empty.
    """
    from ._contact_scan import fill_boxes

    box_v = boxes / pitch
    coords = []
    for a in range(3):
        extra = np.round(box_v[:, :, a].ravel(), 9)
        c = np.unique(np.concatenate([np.arange(grid.shape[a] + 1, dtype=np.float64), extra]))
        c = c[(c >= 0) & (c <= grid.shape[a])]
        if len(c) - 1 > max_side:
            return None
        coords.append(c)
    parts = _refine(grid.astype(np.int64) if labels is None else np.where(grid, labels, 0).astype(np.int64), coords)
    cells = parts > 0
    lo, hi = _box_cells(box_v, coords)
    fill_boxes(cells, parts, lo, hi)  # one slab per bridge box
    if labels is None:
        return cells, tuple(coords)
    return cells, tuple(coords), parts


def _refine(values: npt.NDArray[np.int64], coords: list[npt.NDArray[np.float64]] | tuple[npt.NDArray[np.float64], ...]
            ) -> npt.NDArray[np.int64]:
    """A voxel grid's values on the cells of a refined rectilinear grid (each cell takes its voxel's)."""
    for a, c in enumerate(coords):
        centres = (c[:-1] + c[1:]) / 2
        # Gathering one axis at a time is much faster than fancy indexing with np.ix_.
        values = values.take(np.minimum(np.floor(centres).astype(np.int64), values.shape[a] - 1), axis=a)
    return np.ascontiguousarray(values)


def _box_cells(box_v: npt.NDArray[np.float64], coords: list[npt.NDArray[np.float64]] | tuple[npt.NDArray[np.float64], ...]
               ) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    """The cell ranges ``lo .. hi`` (exclusive) of boxes given in voxels, on the refined grid ``coords``."""
    lo = np.stack([np.searchsorted(coords[a], np.round(box_v[:, 0, a], 9)) for a in range(3)], axis=1)
    hi = np.stack([np.searchsorted(coords[a], np.round(box_v[:, 1, a], 9)) for a in range(3)], axis=1)
    return lo.astype(np.int64), hi.astype(np.int64)


def bridged_colours(
    index: npt.NDArray[np.integer], boxes: npt.NDArray[np.float64], coords: tuple[npt.NDArray[np.float64], ...], *,
    pitch: float, palette: npt.NDArray[np.uint8],
) -> npt.NDArray[np.uint8]:
    """The colour index of every cell of :func:`bridged_grid`'s refined grid.

    A cell inside a voxel takes the voxel's colour; the cells a bridge box adds
    over empty voxels take the colour most of the box's voxel cells have (on a
    tie the smaller RGBA in ``palette``, so that the same colours in another
    palette order bridge alike), so a bridge is one colour of the voxels it joins.
    """
    from ._contact_scan import paint_boxes

    # Paint with ranks of the colours' values, not the palette's order, then go back to indices.
    rgba = np.asarray(palette, dtype=np.int64)[1:, :4]
    by_value = np.lexsort(rgba.T[::-1]) + 1  # indices 1..N in ascending (r, g, b, a)
    rank = np.zeros(len(rgba) + 1, dtype=np.int64)
    rank[by_value] = np.arange(1, len(rgba) + 1)
    colour = _refine(rank[index.astype(np.int64)], coords)
    lo, hi = _box_cells(boxes / pitch, coords)
    paint_boxes(colour, lo, hi)
    return np.concatenate([[0], by_value])[colour].astype(np.uint8)  # the voxels' own type: one mesher
