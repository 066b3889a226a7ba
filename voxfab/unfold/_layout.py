"""From a search state to a Net, and the seams of a net with their tab room.

Cell sides are numbered 0 bottom, 1 right, 2 top, 3 left; a face with rotation
``r`` puts its edge ``k`` (corner k → k+1) on side ``(k + r) % 4``, so its corner
``k`` sits at the cell corner :data:`CELL_CORNER` ``[(k + r) % 4]``.  Cell corners
run counter-clockwise (y up), like the 3D corners seen from outside, so no face is
ever mirrored.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from voxfab.errors import UnfoldError
from voxfab.shape import SurfaceGraph, surface_graph

from ._net import Net

#: Cell corner offsets, counter-clockwise from the bottom left.
CELL_CORNER = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.int64)
#: Cell offset across each side (bottom, right, top, left).
SIDE_STEP = np.array([[0, -1], [1, 0], [0, 1], [-1, 0]], dtype=np.int64)


def build_net(
    sg: SurfaceGraph,
    faces: npt.NDArray[np.int64],
    cell: npt.NDArray[np.int64],
    rot: npt.NDArray[np.int64],
    parent: npt.NDArray[np.int64],
    *,
    seed: int,
    strategy: str,
) -> Net:
    """Assemble a Net from placed faces.

    Parameters
    ----------
    sg : SurfaceGraph
        The shape's surface graph.
    faces : (P,) int ndarray
        Surface-graph indices of the net's faces, increasing.
    cell : (F, 2) int ndarray
        Cell of every surface face (only rows in ``faces`` are read).
    rot : (F,) int ndarray
        Rotation of every surface face.
    parent : (F,) int ndarray
        Fold-tree parent (-1 for the root).
    seed, strategy
        Recorded in the net.

    Returns
    -------
    Net
        Corners shifted so the net's lower-left corner is (0, 0).  Folds are the
        tree edges plus every cut edge whose two sides meet in the plane (such a
        cut would be a slit).
    """
    faces = np.asarray(faces, dtype=np.int64)
    local = np.full(sg.face_count, -1, dtype=np.int64)
    local[faces] = np.arange(faces.size)
    k = np.arange(4)
    c2 = cell[faces][:, None, :] + CELL_CORNER[(k[None, :] + rot[faces][:, None]) % 4]
    c2 = c2 - c2.reshape(-1, 2).min(axis=0)
    a = np.repeat(faces, 4)
    kk = np.tile(k, faces.size)
    b = sg.neighbor[a, kk]
    inside = local[b] >= 0
    a, kk, b = a[inside], kk[inside], b[inside]
    tree = (parent[b] == a) | (parent[a] == b)
    side = (kk + rot[a]) % 4
    meets = (cell[a] + SIDE_STEP[side] == cell[b]).all(axis=1) & (
        rot[b] == (side + 2 - sg.neighbor_edge[a, kk]) % 4
    )
    keep = (tree | meets) & (a < b)
    pairs = np.stack([local[a[keep]], local[b[keep]]], axis=1)
    order = np.lexsort((pairs[:, 1], pairs[:, 0]))
    pairs = pairs[order]
    kinds = sg.fold[a[keep], kk[keep]][order]
    return Net(
        voxel=sg.voxel[faces],
        normal=sg.normal[faces],
        corners3d=sg.corners[faces],
        corners2d=c2,
        folds=pairs if pairs.size else np.zeros((0, 2), dtype=np.int64),
        seed=int(seed),
        strategy=strategy,
        mountain=int(np.count_nonzero(kinds == 1)),
        valley=int(np.count_nonzero(kinds == -1)),
        flat=int(np.count_nonzero(kinds == 0)),
    )


def _face_ids(sg: SurfaceGraph, net: Net) -> npt.NDArray[np.int64]:
    """Surface-graph index of each net face, matched by (voxel, normal)."""
    if net.face_count == sg.face_count and np.array_equal(net.voxel, sg.voxel) and np.array_equal(
            net.normal, sg.normal):
        return np.arange(sg.face_count, dtype=np.int64)  # a whole net lists the faces in surface-graph order
    key_sg = {
        (tuple(v), tuple(n)): i for i, (v, n) in enumerate(zip(sg.voxel.tolist(), sg.normal.tolist()))
    }
    ids = np.empty(net.face_count, dtype=np.int64)
    for t, (v, n) in enumerate(zip(net.voxel.tolist(), net.normal.tolist())):
        i = key_sg.get((tuple(v), tuple(n)))
        if i is None:
            raise UnfoldError(f"net face {t} (voxel {v}, normal {n}) is not a face of the shape")
        ids[t] = i
    return ids


def seam_pairs(grid: npt.ArrayLike, net: Net) -> npt.NDArray[np.int64]:
    """The cut seams of a net.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The shape the net unfolds.
    net : Net
        A net of that shape, or one piece of a several-piece unfolding.

    Returns
    -------
    (S, 2, 2) int64 ndarray
        For each seam, ``[[face, edge], [face, edge]]`` of its two sides, faces as
        indices into ``net``'s face list, the smaller face first, rows sorted.
        Seams whose other side lies in another piece are left out.
    """
    sg = surface_graph(grid)
    ids = _face_ids(sg, net)
    local = np.full(sg.face_count, -1, dtype=np.int64)
    local[ids] = np.arange(ids.size)
    n = ids.size
    folds = net.folds.reshape(-1, 2)
    folded = np.minimum(folds[:, 0], folds[:, 1]) * n + np.maximum(folds[:, 0], folds[:, 1])
    other = local[sg.neighbor[ids]]  # (n, 4) net face across each edge, -1 outside this net
    t = np.arange(n)[:, None]
    keep = (other > t) & ~np.isin(t * n + other, folded)
    tt, kk = np.nonzero(keep)  # face by face, edge by edge
    uu = other[tt, kk]
    return np.stack([np.stack([tt, kk], axis=1), np.stack([uu, sg.neighbor_edge[ids[tt], kk]], axis=1)],
                    axis=1).astype(np.int64)


def tab_room(grid: npt.ArrayLike, net: Net) -> npt.NDArray[np.bool_]:
    """Whether each seam side has a free cell beyond its edge for a glue tab.

    Returns
    -------
    (S, 2) bool ndarray
        Row s matches row s of :func:`seam_pairs`; a seam has tab room when at
        least one of its two entries is True.
    """
    seams = seam_pairs(grid, net)
    c2 = net.corners2d
    cells = c2.min(axis=1)
    f, k = seams[:, :, 0], seams[:, :, 1]
    p, q = c2[f, k], c2[f, (k + 1) % 4]
    step = np.stack([q[..., 1] - p[..., 1], p[..., 0] - q[..., 0]], axis=-1)  # right of a CCW edge = outside
    beyond = cells[f] + step
    lo = cells.min(axis=0) - 1
    span = int((cells.max(axis=0) - lo).max()) + 2

    def key(c: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
        return (c[..., 0] - lo[0]) * span + (c[..., 1] - lo[1])

    return ~np.isin(key(beyond), key(cells))


def count_without_tab_room(grid: npt.ArrayLike, net: Net) -> int:
    """Number of seams neither of whose sides has tab room."""
    room = tab_room(grid, net)
    return int(np.count_nonzero(~room.any(axis=1))) if room.size else 0
