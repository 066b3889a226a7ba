"""The surface graph: exposed voxel faces and their neighbours by the 6-connectivity rule.

This is the one place where voxfab decides which faces meet along an edge.  Nets,
meshes and drawings all read it, so they agree on every fold and every vertex.

Conventions
-----------
A face is a pair (voxel v, outward direction d) with ``d`` in ``0..5`` standing
for +x, -x, +y, -y, +z, -z (:data:`DIRECTIONS`).  Its four corners are listed
counter-clockwise seen from outside, in voxel-corner integer coordinates (voxel
``(x, y, z)`` spans ``[x, x+1]×[y, y+1]×[z, z+1]``).  Edge ``k`` runs from corner
``k`` to corner ``k+1``, and :data:`EDGE_OUT` ``[d, k]`` is the in-plane unit
direction pointing out of the face across edge ``k``.

Across edge ``k`` with outward direction ``u``, the neighbour of face (v, n) is:

* (v+u+n, −u) when v+u and v+u+n are filled: a valley (concave) fold;
* (v+u, n) when only v+u is filled: flat, coplanar;
* (v, u) when v+u is empty: a mountain (convex) fold.

So two voxels that touch only along an edge or at a corner stay apart.
"""

from __future__ import annotations

import dataclasses
from functools import cached_property

import numpy as np
import numpy.typing as npt

from voxfab._shared.validate import as_grid

__all__ = [
    "DIRECTIONS",
    "EDGE_OUT",
    "CORNER_OFFSETS",
    "FOLD_FLAT",
    "FOLD_MOUNTAIN",
    "FOLD_VALLEY",
    "SurfaceGraph",
    "surface_graph",
]

#: Outward unit normals of the six face directions, indexed by ``d``.
DIRECTIONS = np.array(
    [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=np.int64
)

FOLD_FLAT = 0
FOLD_MOUNTAIN = 1
FOLD_VALLEY = -1


def _direction_index(vec: npt.ArrayLike) -> int:
    return int(np.flatnonzero((DIRECTIONS == np.asarray(vec)).all(axis=1))[0])


def _face_tables() -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    corners = np.zeros((6, 4, 3), dtype=np.int64)
    edge_out = np.zeros((6, 4), dtype=np.int64)
    for d in range(6):
        a = d // 2
        positive = d % 2 == 0
        # (b, c, a) is cyclic, so e_b × e_c = e_a and (b, c) is counter-clockwise seen from +a.
        b, c = (a + 1) % 3, (a + 2) % 3
        bc = [(0, 0), (1, 0), (1, 1), (0, 1)] if positive else [(0, 0), (0, 1), (1, 1), (1, 0)]
        for k, (pb, pc) in enumerate(bc):
            corners[d, k, a] = 1 if positive else 0
            corners[d, k, b] = pb
            corners[d, k, c] = pc
        for k in range(4):
            p, q = corners[d, k], corners[d, (k + 1) % 4]
            mid = (p + q) / 2.0
            centre = corners[d].mean(axis=0)
            u = np.rint((mid - centre) * 2).astype(np.int64)
            u[a] = 0
            edge_out[d, k] = _direction_index(u)
    return corners, edge_out


#: ``CORNER_OFFSETS[d]``: the 4 corners of a face of direction d of the voxel at the origin.
#: ``EDGE_OUT[d, k]``: direction index of the outward in-plane normal of edge k.
CORNER_OFFSETS, EDGE_OUT = _face_tables()
#: ``EDGE_OF[d, e]``: the edge k of a face of direction d whose outward direction is e (-1: none).
EDGE_OF = np.full((6, 6), -1, dtype=np.int64)
for _d in range(6):
    for _k in range(4):
        EDGE_OF[_d, EDGE_OUT[_d, _k]] = _k
_OPPOSITE = np.array([1, 0, 3, 2, 5, 4], dtype=np.int64)


@dataclasses.dataclass(frozen=True, eq=False)
class SurfaceGraph:
    """The exposed faces of a voxel shape and how they meet.

    Attributes
    ----------
    voxel : (F, 3) int64 ndarray
        The filled voxel each face belongs to.
    direction : (F,) int64 ndarray
        The face's outward direction index (see :data:`DIRECTIONS`).
    neighbor : (F, 4) int64 ndarray
        ``neighbor[f, k]``: the face across edge ``k`` of face ``f``.
    neighbor_edge : (F, 4) int64 ndarray
        The edge index of that shared edge as seen from the neighbour.
    fold : (F, 4) int8 ndarray
        ``FOLD_MOUNTAIN`` (+1, convex), ``FOLD_VALLEY`` (−1, concave) or ``FOLD_FLAT`` (0).

    Faces are sorted by ``(x, y, z, d)``.
    """

    voxel: npt.NDArray[np.int64]
    direction: npt.NDArray[np.int64]
    neighbor: npt.NDArray[np.int64]
    neighbor_edge: npt.NDArray[np.int64]
    fold: npt.NDArray[np.int8]

    @property
    def face_count(self) -> int:
        """Number of exposed faces F."""
        return int(self.direction.shape[0])

    @property
    def normal(self) -> npt.NDArray[np.int64]:
        """``(F, 3)`` outward unit normals."""
        return DIRECTIONS[self.direction]

    @property
    def corners(self) -> npt.NDArray[np.int64]:
        """``(F, 4, 3)`` face corners, counter-clockwise seen from outside."""
        return self.voxel[:, None, :] + CORNER_OFFSETS[self.direction]

    @cached_property
    def vertex(self) -> npt.NDArray[np.int64]:
        """``(F, 4)`` vertex id of each face corner, split by the 6-connectivity rule.

        Corners are one vertex exactly when they are joined through a chain of
        faces adjacent in this graph around that point, so voxels touching only
        at a corner get separate vertices there, and so do voxels touching only
        along an edge unless both ends of that edge are joined around: then the
        edge is used twice by index (a pinch that only a change of geometry, such
        as a bridge, can remove).  Every other edge is used by exactly two faces.
        """
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        f = self.face_count
        faces = np.repeat(np.arange(f), 4)
        k = np.tile(np.arange(4), f)
        nb = self.neighbor.ravel()
        kk = self.neighbor_edge.ravel()
        # Edge k runs corner k -> k+1; the neighbour runs the same edge backwards,
        # so our corner k is its corner kk+1.
        a = faces * 4 + k
        b = nb * 4 + (kk + 1) % 4
        m = coo_matrix((np.ones(a.size, dtype=np.int8), (a, b)), shape=(4 * f, 4 * f))
        _, labels = connected_components(m, directed=False)
        # Renumber in order of first appearance so ids are deterministic and dense.
        _, first, inverse = np.unique(labels, return_index=True, return_inverse=True)
        order = np.argsort(np.argsort(first))
        return order[inverse].reshape(f, 4).astype(np.int64)

    @cached_property
    def vertex_position(self) -> npt.NDArray[np.int64]:
        """``(V, 3)`` integer position of each vertex id."""
        pos = np.zeros((int(self.vertex.max()) + 1, 3), dtype=np.int64)
        pos[self.vertex.ravel()] = self.corners.reshape(-1, 3)
        return pos

    def fold_counts(self) -> dict[str, int]:
        """Number of mountain, valley and flat surface edges (each edge once)."""
        return {
            "mountain": int(np.count_nonzero(self.fold == FOLD_MOUNTAIN)) // 2,
            "valley": int(np.count_nonzero(self.fold == FOLD_VALLEY)) // 2,
            "flat": int(np.count_nonzero(self.fold == FOLD_FLAT)) // 2,
        }


def surface_graph(grid: npt.ArrayLike) -> SurfaceGraph:
    """Build the surface graph of a voxel shape.

    Parameters
    ----------
    grid : (X, Y, Z) bool array_like
        The shape, indexed ``[x, y, z]``.

    Returns
    -------
    SurfaceGraph
        Every exposed face with its four neighbours and fold types.
    """
    g = as_grid(grid)
    p = np.pad(g, 1)
    dims = np.array(p.shape, dtype=np.int64)
    strides = np.array([dims[1] * dims[2], dims[2], 1], dtype=np.int64)
    flat = p.ravel()
    # A face is keyed by (flat index of its voxel in the padded grid) * 6 + d, so
    # sorting keys sorts faces by (x, y, z, d), and neighbours are found by binary
    # search: no dense (X, Y, Z, 6) id array, which would cost ~0.4 GB at 256³.
    parts = []
    for d, (dx, dy, dz) in enumerate(DIRECTIONS):
        exposed = p & ~np.roll(p, (-dx, -dy, -dz), axis=(0, 1, 2))
        parts.append(np.flatnonzero(exposed) * 6 + d)
    keys = np.sort(np.concatenate(parts))
    nf = keys.size
    cell = keys // 6
    ds = keys % 6
    v = np.stack([cell // strides[0], (cell // strides[1]) % dims[1], cell % dims[2]], axis=1)
    step = DIRECTIONS @ strides  # flat-index offset of each direction

    neighbor = np.empty((nf, 4), dtype=np.int64)
    neighbor_edge = np.empty((nf, 4), dtype=np.int64)
    fold = np.empty((nf, 4), dtype=np.int8)
    for k in range(4):
        ue = EDGE_OUT[ds, k]
        side = cell + step[ue]
        over = side + step[ds]
        f_side = flat[side]
        f_over = flat[over]
        valley = f_side & f_over
        flat_fold = f_side & ~f_over
        ncell = np.where(valley, over, np.where(flat_fold, side, cell))
        ndir = np.where(valley, _OPPOSITE[ue], np.where(flat_fold, ds, ue))
        # Outward direction of the shared edge as seen from the neighbour.
        nedge_out = np.where(valley, _OPPOSITE[ds], np.where(flat_fold, _OPPOSITE[ue], ds))
        nkey = ncell * 6 + ndir
        idx = np.searchsorted(keys, nkey)
        # The rule always lands on an exposed face; anything else is a bug here.
        assert (keys[np.minimum(idx, nf - 1)] == nkey).all(), "surface graph rule broken"
        neighbor[:, k] = idx
        neighbor_edge[:, k] = EDGE_OF[ndir, nedge_out]
        fold[:, k] = np.where(valley, FOLD_VALLEY, np.where(flat_fold, FOLD_FLAT, FOLD_MOUNTAIN))
    return SurfaceGraph(
        voxel=v - 1,
        direction=ds.astype(np.int64),
        neighbor=neighbor,
        neighbor_edge=neighbor_edge,
        fold=fold,
    )
