"""Net geometry: which edges are folds, seams or slits, merged lines and cut outlines.

Everything here works on whole arrays of face edges.  Edge ``k`` of face ``f``
runs from 2D corner ``k`` to corner ``k+1``; corners are counter-clockwise, so
the face lies on the left of each of its edges and the outside on the right.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import numpy.typing as npt

from voxfab._shared.arrays import unique
from voxfab.errors import FormatError
from voxfab.shape import SurfaceGraph
from voxfab.unfold import Net

_NEXT = np.array([1, 2, 3, 0])


@dataclasses.dataclass(frozen=True, eq=False)
class NetEdges:
    """Classification of every face edge of a net.

    Attributes
    ----------
    joined : (F, 4) bool ndarray
        The edge stays connected in the drawing (a fold of the net, or a seam whose
        two sides already meet in the plane and is left uncut).
    closed_in_plane : (F, 4) bool ndarray
        Seams of the net left uncut because both sides meet in the plane.
    fold_type : (F, 4) int8 ndarray
        +1 mountain (convex), -1 valley (concave), 0 coplanar.
    partner_face, partner_edge : (F, 4) int ndarray
        The face and edge glued to or folded with each edge; the face is -1 when
        it belongs to another piece.
    global_low : (F, 4) bool ndarray
        The edge is the copy seen from the lower surface-graph face of the two.
    seam_id : (F, 4) int ndarray
        Index of the edge among all surface edges, the same on both copies (used
        to number seams that run between pieces).
    """

    joined: npt.NDArray[np.bool_]
    closed_in_plane: npt.NDArray[np.bool_]
    fold_type: npt.NDArray[np.int8]
    partner_face: npt.NDArray[np.int64]
    partner_edge: npt.NDArray[np.int64]
    global_low: npt.NDArray[np.bool_]
    seam_id: npt.NDArray[np.int64]

    @property
    def external(self) -> npt.NDArray[np.bool_]:
        """``(F, 4)`` edges glued to another piece."""
        return self.partner_face < 0

    def canonical(self) -> npt.NDArray[np.bool_]:
        """``(F, 4)`` mask choosing one copy of every edge (the only copy of an external one)."""
        f = np.arange(self.joined.shape[0])[:, None]
        k = np.arange(4)[None, :]
        g, kk = self.partner_face, self.partner_edge
        return (g < 0) | (f < g) | ((f == g) & (k < kk))


def face_map(graph: SurfaceGraph, net: Net) -> npt.NDArray[np.int64]:
    """``(n,)`` surface-graph face of each net face, matched by voxel and normal.

    A whole net lists the faces in surface-graph order; a piece of a several-piece
    unfolding lists some of them in its own order.

    Raises
    ------
    FormatError
        When a net face is not an exposed face of the shape, appears twice, or
        lists its corners differently.
    """
    if net.face_count == graph.face_count and np.array_equal(net.corners3d, graph.corners):
        return np.arange(graph.face_count, dtype=np.int64)
    lo = np.minimum(graph.voxel.min(axis=0), net.voxel.min(axis=0) if net.face_count else 0) - 1
    span = np.maximum(graph.voxel.max(axis=0), net.voxel.max(axis=0) if net.face_count else 0) - lo + 2

    def key(voxel: npt.NDArray[np.int64], direction: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
        v = voxel - lo
        return ((v[:, 0] * span[1] + v[:, 1]) * span[2] + v[:, 2]) * 6 + direction

    from voxfab.shape import DIRECTIONS

    match = (net.normal[:, None, :] == DIRECTIONS[None, :, :]).all(axis=2)
    if not match.any(axis=1).all():
        raise FormatError("net: a face normal is not a unit axis vector")
    graph_keys = key(graph.voxel, graph.direction)
    net_keys = key(net.voxel, match.argmax(axis=1))
    pos = np.searchsorted(graph_keys, net_keys)
    pos = np.minimum(pos, graph_keys.size - 1)
    found = graph_keys[pos] == net_keys
    if not found.all() or unique(pos).size != pos.size or not np.array_equal(net.corners3d, graph.corners[pos]):
        raise FormatError(
            f"net: its {net.face_count} faces do not match the shape's {graph.face_count} "
            "surface faces (a net of another shape?)"
        )
    return pos.astype(np.int64)


def check_net(graph: SurfaceGraph, net: Net) -> None:
    """Raise FormatError when ``net`` is not a net (or a net piece) of the surface ``graph``."""
    face_map(graph, net)


def classify_edges(graph: SurfaceGraph, net: Net, corners2d: npt.NDArray[np.int64]) -> NetEdges:
    """Classify the edges of ``net`` laid out at ``corners2d`` (n, 4, 2) integer cells.

    For a piece of a several-piece unfolding, edges glued to faces of other
    pieces get partner face -1 and a global ``seam_id`` shared with those pieces.

    Raises
    ------
    FormatError
        When a fold of the net joins faces that are not neighbours in the surface
        graph or whose shared edge does not coincide in the layout.
    """
    fid = face_map(graph, net)
    n = fid.size
    local = np.full(graph.face_count, -1, dtype=np.int64)
    local[fid] = np.arange(n)
    g_global = graph.neighbor[fid]
    g = local[g_global]
    kk = graph.neighbor_edge[fid]
    inside = g >= 0
    folds = net.folds
    if folds.size and (folds.min() < 0 or folds.max() >= n):
        raise FormatError("net: a fold names a face the net does not have")
    fold_keys = unique(np.minimum(folds[:, 0], folds[:, 1]) * n + np.maximum(folds[:, 0], folds[:, 1]))
    f = np.repeat(np.arange(n)[:, None], 4, axis=1)
    edge_keys = np.where(inside, np.minimum(f, g) * n + np.maximum(f, g), -1)
    is_fold = np.isin(edge_keys, fold_keys) & inside
    if np.count_nonzero(is_fold) != 2 * fold_keys.size:
        raise FormatError("net: a fold joins two faces that do not share an edge on the surface")
    gs = np.where(inside, g, 0)
    p0 = corners2d
    p1 = corners2d[:, _NEXT]
    q0 = corners2d[gs, kk]
    q1 = corners2d[gs, _NEXT[kk]]
    meets = (q0 == p1).all(axis=-1) & (q1 == p0).all(axis=-1) & inside
    if not meets[is_fold].all():
        bad = np.argwhere(is_fold & ~meets)[0]
        raise FormatError(
            f"net: fold between faces {bad[0]} and {g[bad[0], bad[1]]} is not a shared edge in the layout"
        )
    closed = meets & ~is_fold
    # Global id of every surface edge: its rank among the edges seen from their lower face.
    gf = np.arange(graph.face_count)[:, None]
    low = (gf < graph.neighbor) | ((gf == graph.neighbor) & (np.arange(4) < graph.neighbor_edge))
    rank = np.cumsum(low.ravel()).reshape(low.shape) - 1
    rank = np.where(low, rank, rank[graph.neighbor, graph.neighbor_edge])
    return NetEdges(
        joined=is_fold | closed,
        closed_in_plane=closed,
        fold_type=graph.fold[fid].astype(np.int8),
        partner_face=g,
        partner_edge=kk,
        global_low=low[fid],
        seam_id=rank[fid],
    )


def merge_unit_segments(a: npt.NDArray[np.int64], b: npt.NDArray[np.int64]) -> tuple[np.ndarray, np.ndarray]:
    """Merge axis-aligned unit lattice segments into maximal straight runs.

    Parameters
    ----------
    a, b : (N, 2) int ndarray
        Segment end points on the integer lattice, each of length 1.  Duplicates
        are drawn once.

    Returns
    -------
    start, end : (M, 2) int ndarray
        The runs, sorted (horizontal ones first, then by line and position).
    """
    if a.shape[0] == 0:
        return np.zeros((0, 2), dtype=np.int64), np.zeros((0, 2), dtype=np.int64)
    lo = np.minimum(a, b)
    horizontal = a[:, 1] == b[:, 1]
    # (axis, line coordinate, position along the line) for every unit segment.
    axis = np.where(horizontal, 0, 1)
    line = np.where(horizontal, lo[:, 1], lo[:, 0])
    pos = np.where(horizontal, lo[:, 0], lo[:, 1])
    key = unique(np.stack([axis, line, pos], axis=1), axis=0)
    new_run = np.ones(key.shape[0], dtype=bool)
    new_run[1:] = (key[1:, 0] != key[:-1, 0]) | (key[1:, 1] != key[:-1, 1]) | (key[1:, 2] != key[:-1, 2] + 1)
    starts = np.flatnonzero(new_run)
    ends = np.concatenate([starts[1:], [key.shape[0]]]) - 1
    ax, ln, p_start, p_end = key[starts, 0], key[starts, 1], key[starts, 2], key[ends, 2] + 1
    start = np.where(ax[:, None] == 0, np.stack([p_start, ln], 1), np.stack([ln, p_start], 1))
    end = np.where(ax[:, None] == 0, np.stack([p_end, ln], 1), np.stack([ln, p_end], 1))
    return start, end


def drop_collinear(ring: npt.NDArray[np.float64], *, tol: float = 1e-9) -> npt.NDArray[np.float64]:
    """Remove repeated and collinear vertices of a closed ring (given without its closing point)."""
    r = ring
    for _ in range(3):
        if r.shape[0] < 3:
            return r
        prev = np.roll(r, 1, axis=0)
        nxt = np.roll(r, -1, axis=0)
        u = r - prev
        v = nxt - r
        cross = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
        scale = np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1)
        dup = np.linalg.norm(u, axis=1) <= tol
        straight = (np.abs(cross) <= tol * np.maximum(scale, 1.0)) & ((u * v).sum(axis=1) > 0)
        keep = ~(dup | straight)
        if keep.all():
            return r
        r = r[keep]
    return r


def trace_outlines(
    p0: npt.NDArray[np.int64],
    p1: npt.NDArray[np.int64],
    detour: npt.NDArray[np.float64],
    *,
    origin: npt.NDArray[np.float64],
    pitch: float,
) -> tuple[list[npt.NDArray[np.float64]], int]:
    """Closed cut outlines from the boundary edges of a set of faces.

    Parameters
    ----------
    p0, p1 : (E, 2) int ndarray
        Boundary unit edges in cells, directed with their face on the left (so
        outer boundaries run counter-clockwise and holes clockwise).
    detour : (E, 4, 2) float ndarray
        Points (mm) the outline visits between ``p0`` and ``p1`` to go round a
        glue tab, NaN where the edge has no tab.
    origin : (2,) float ndarray
        Position of cell (0, 0), mm.
    pitch : float
        Cell size, mm.

    Returns
    -------
    rings : list of (n, 2) float ndarray
        Closed rings without their closing point and without collinear vertices,
        outer boundaries (one per piece) first, then holes.
    pieces : int
        Number of outer boundaries.

    Notes
    -----
    Where the boundary touches itself at a vertex (two faces meeting only at a
    corner), the walk takes the leftmost turn, so each ring keeps to one side and
    no ring crosses another; every edge is used exactly once.
    """
    n_edges = p0.shape[0]
    out: dict[tuple[int, int], list[int]] = {}
    for i, v in enumerate(map(tuple, p0.tolist())):
        out.setdefault(v, []).append(i)
    ends = list(map(tuple, p1.tolist()))
    direction = (p1 - p0).tolist()
    has_detour = ~np.isnan(detour[:, 0, 0])
    used = [False] * n_edges
    rings: list[npt.NDArray[np.float64]] = []
    for first in range(n_edges):
        if used[first]:
            continue
        chain = [first]
        used[first] = True
        e = first
        while True:
            options = [c for c in out[ends[e]] if not used[c] or c == first]
            if len(options) > 1:
                ux, uy = direction[e]
                # Leftmost turn: left (+1) before straight (0) before right (-1).
                options.sort(key=lambda c: -(ux * direction[c][1] - uy * direction[c][0]))
            e = options[0]
            if e == first:
                break
            used[e] = True
            chain.append(e)
        idx = np.array(chain)
        start = origin + p0[idx] * pitch
        pts = np.concatenate([start[:, None, :], detour[idx]], axis=1).reshape(-1, 2)
        keep = np.concatenate([np.ones((idx.size, 1), dtype=bool), np.repeat(has_detour[idx, None], 4, axis=1)],
                              axis=1).ravel()
        rings.append(drop_collinear(pts[keep]))
    outer = [r for r in rings if _signed_area(r) > 0]
    holes = [r for r in rings if _signed_area(r) <= 0]
    return outer + holes, len(outer)


def _signed_area(ring: npt.NDArray[np.float64]) -> float:
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def piece_labels(joined: npt.NDArray[np.bool_], partner_face: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
    """``(F,)`` connected-component label of each face through joined edges."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    f_count = joined.shape[0]
    f = np.repeat(np.arange(f_count), 4)
    g = partner_face.ravel()
    m = joined.ravel()
    adj = coo_matrix((np.ones(int(m.sum()), dtype=np.int8), (f[m], g[m])), shape=(f_count, f_count))
    _, labels = connected_components(adj, directed=False)
    return labels.astype(np.int64)
