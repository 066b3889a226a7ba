"""Cut paths: nets whose cut edges form one path through the surface's vertices, the model and its checks.

The zipper search (:mod:`._zipper`, every vertex on the path) and the
census's edge-unzipping (:mod:`voxfab.census`, flat vertices optional) share
all of it: the path as one ``AddCircuit`` over the vertices and a dummy node,
the short fold paths that overlap ruled out first, and the development of a
path's uncut edges, whose overlaps become no-goods
(:func:`._cpsat.solve_with_nogoods`).
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np
import numpy.typing as npt

from voxfab.shape import SurfaceGraph

from ._constraints import _SIDE_STEP
from ._cpsat import cp_model
from ._exact import Undecided

__all__ = ["cell_clashes", "fold_flat", "path_model", "short_overlaps", "surface_edges", "tree_path"]

#: An edge of the surface between faces ``a`` and ``b``: face a's edge k is face b's edge kb.
Edge = tuple[int, int, int, int]


def surface_edges(sg: SurfaceGraph, faces: npt.NDArray[np.int64]) -> list[Edge]:
    """Each surface edge between two faces of ``faces`` once, as ``(a, k, b, kb)`` with ``(a, k) < (b, kb)``."""
    inside = np.zeros(sg.face_count, dtype=bool)
    inside[faces] = True
    out = []
    for a in faces.tolist():
        for k in range(4):
            b, kb = int(sg.neighbor[a, k]), int(sg.neighbor_edge[a, k])
            if b >= 0 and inside[b] and (a, k) < (b, kb):
                out.append((a, k, b, kb))
    return out


def path_model(sg: SurfaceGraph, faces: npt.NDArray[np.int64], edges: list[Edge], *,
               optional: npt.NDArray[np.bool_] | None = None) -> tuple[Any, list[tuple[Any, Any]]]:
    """A CP-SAT model whose solutions are the paths along ``edges`` through the vertices of ``faces``.

    Parameters
    ----------
    sg : SurfaceGraph
    faces : (P,) int ndarray
        The faces of one connected surface part, increasing.
    edges : list of (int, int, int, int)
        :func:`surface_edges` of ``faces``.
    optional : (V,) bool ndarray, optional
        Vertices (by surface vertex index) the path may leave out; it ends at
        the others.  None: every vertex is on the path.

    Returns
    -------
    model : ortools CpModel
    cut : list of (literal, literal)
        For edge ``i``, "the path walks it from its first vertex to its second"
        and the reverse: the edge is cut when either holds.

    Notes
    -----
    The path's two ends are joined through a dummy node into one circuit; a
    self-loop on an optional vertex means "not on the path".  A path and its
    reverse are one cut: the end at the lower vertex is its start.
    """
    m = cp_model().CpModel()
    verts = np.unique(sg.vertex[faces])
    index = {int(v): i for i, v in enumerate(verts.tolist())}
    dummy = int(verts.size)
    arcs: list[tuple[int, int, Any]] = []
    cut = []
    for i, (a, k, _, _) in enumerate(edges):
        u, v = index[int(sg.vertex[a, k])], index[int(sg.vertex[a, (k + 1) % 4])]
        uv, vu = m.new_bool_var(f"u{i}"), m.new_bool_var(f"v{i}")
        arcs += [(u, v, uv), (v, u, vu)]
        cut.append((uv, vu))
    starts, ends = [], []
    for v in range(dummy):
        if optional is None or not optional[verts[v]]:
            s, t = m.new_bool_var(f"s{v}"), m.new_bool_var(f"t{v}")
            arcs += [(dummy, v, s), (v, dummy, t)]
            starts.append(s)
            ends.append(t)
        else:
            arcs.append((v, v, m.new_bool_var(f"skip{v}")))
    m.add_circuit(arcs)
    for j in range(len(starts)):
        m.add(sum(ends[: j + 1]) >= 1).only_enforce_if(starts[j])
    return m, cut


def fold_flat(faces: npt.NDArray[np.int64], folds: list[Edge], f: int):  # noqa: ANN201
    """Cells, rotations, parents (from ``faces[0]``) and the fold into each face of the tree ``folds``.

    Folds beyond a spanning tree (closing round a flat vertex) are left out of
    the walk; the fold into a face is its index in ``folds``.
    """
    adj: dict[int, list[tuple[int, int, int, int]]] = {}
    for i, (a, k, b, kb) in enumerate(folds):
        adj.setdefault(a, []).append((k, b, kb, i))
        adj.setdefault(b, []).append((kb, a, k, i))
    cell = np.zeros((f, 2), dtype=np.int64)
    rot = np.zeros(f, dtype=np.int64)
    parent = np.full(f, -1, dtype=np.int64)
    via = np.full(f, -1, dtype=np.int64)  # index in ``folds`` of the fold from the parent
    root = int(faces[0])
    seen = {root}
    queue = [root]
    for a in queue:  # breadth first, neighbours in edge order: a fixed layout
        for k, b, kb, i in adj.get(a, ()):
            if b in seen:
                continue
            seen.add(b)
            s = (k + int(rot[a])) % 4
            cell[b] = cell[a] + _SIDE_STEP[s]
            rot[b] = (s + 2 - kb) % 4
            parent[b], via[b] = a, i
            queue.append(b)
    return cell, rot, parent, via


def cell_clashes(faces: npt.NDArray[np.int64], cell: npt.NDArray[np.int64]) -> list[tuple[int, int]]:
    """Pairs of faces laid on one cell: each face after the first on a cell, with that first one."""
    owner: dict[tuple[int, int], int] = {}
    clashes = []
    for a in faces.tolist():
        c = (int(cell[a, 0]), int(cell[a, 1]))
        if c in owner:
            clashes.append((owner[c], a))
        else:
            owner[c] = a
    return clashes


def tree_path(u: int, v: int, parent: npt.NDArray[np.int64], via: npt.NDArray[np.int64]) -> list[int]:
    """Indices of the folds on the tree path between faces ``u`` and ``v``."""
    up_u: dict[int, list[int]] = {}
    path: list[int] = []
    a = u
    while a >= 0:
        up_u[a] = list(path)
        if parent[a] >= 0:
            path.append(int(via[a]))
        a = int(parent[a])
    path_v: list[int] = []
    b = v
    while b not in up_u:
        path_v.append(int(via[b]))
        b = int(parent[b])
    return up_u[b] + path_v


def short_overlaps(sg: SurfaceGraph, faces: npt.NDArray[np.int64], edges: list[Edge],
                   longest: int, deadline: float) -> list[tuple[int, ...]]:
    """Every path of at most ``longest`` folds whose two end faces fold onto one cell (indices in ``edges``).

    Only the shortest such paths are kept (a path holding one is not extended),
    each once whichever end it starts from.  :class:`Undecided` when the deadline passes first.
    """
    # Plain lists: this loop visits every short path, and numpy scalars are slow to index one by one.
    step = [[None] * 4 for _ in range(sg.face_count)]  # (neighbour, its edge, fold index) across each edge
    for i, (a, k, b, kb) in enumerate(edges):
        step[a][k] = (b, kb, i)
        step[b][kb] = (a, k, i)
    side = [tuple(d) for d in _SIDE_STEP]
    found: set[tuple[int, ...]] = set()
    for start in faces.tolist():
        if time.monotonic() > deadline:
            raise Undecided(f"undecided: the zipper search ran out of time while it prepared the {faces.size}-face "
                            "surface; raise the timeout")
        # Depth first: (face, its rotation, its cell, the cells of the path's faces, the folds).
        stack = [(start, 0, 0, 0, {(0, 0): start}, ())]
        while stack:
            a, r, cx, cy, cells, path = stack.pop()
            left = longest - len(path) - 1
            if left < 0:
                continue
            for k in range(4):
                nxt = step[a][k]
                if nxt is None:
                    continue
                b, kb, i = nxt
                if b in cells.values():
                    continue  # not a simple path
                s = (k + r) % 4
                bx, by = cx + side[s][0], cy + side[s][1]
                if (bx, by) in cells:
                    if cells[(bx, by)] == start:
                        found.add(tuple(sorted((*path, i))))
                    continue  # a shorter path inside this one overlaps: it is found from its own start
                if abs(bx) + abs(by) > left:
                    continue  # too far to come back to the start's cell
                stack.append((b, (s + 2 - kb) % 4, bx, by, {**cells, (bx, by): b}, (*path, i)))
    return sorted(found)
