"""Zipper nets in any box: the cut edges as one Hamiltonian path, overlaps refused lazily, on CP-SAT.

A zipper net's cut edges form one path through every vertex of the surface
(they are connected and reach every vertex, and no vertex has three).  On a
surface of genus 0 the edges left uncut are then a spanning tree of the faces
(Euler: ``F - 1 = E - (V - 1)``), so a zipper net *is* a Hamiltonian path of
the vertex graph whose complement folds flat without overlap.  The model is
that path alone, one ``AddCircuit`` over the vertices and a dummy node (a far
stronger propagator than a tree encoded by depths), with no cells at all:

0. the short paths whose ends fold onto one cell (five faces round a vertex
   span 450 degrees, a path round a notch doubles back) are found by a
   bounded enumeration and ruled out first: one of their edges is cut;
1. solve for a Hamiltonian path;
2. fold its complement flat (the layout of a tree is fixed by its folds);
3. two faces on one cell are an overlap that every tree holding the tree path
   between them repeats, so "one of these edges is cut" is added (a no-good),
   and the search goes on from 1.

The loop ends with a net, with a proof that none exists (the path model
with its no-goods, each of them valid, is infeasible), or at the deadline.
A surface with a handle has no zipper net (its cut edges hold a cycle), which
the Euler count shows with no search; nor has a surface whose vertices of the
two lattice colours (``x + y + z`` even or odd) differ by more than one, since
every edge joins two colours (the 2x2x2 cube: 14 and 12).  One worker and a fixed seed make every
step, and so the net, the same on every run.
"""

from __future__ import annotations

import time

import numpy as np
import numpy.typing as npt

from voxfab.errors import NoNetExistsError, UnfoldError
from voxfab.shape import SurfaceGraph

from ._constraints import _SIDE_STEP
from ._exact import ExactLayout, Undecided, _cp_model, _solve, one_worker_solver

__all__ = ["zipper_layout"]

#: Paths of up to this many folds that overlap are ruled out before the search (the common,
#: local overlaps); longer ones as the search meets them.
_SHORT_PATH = 6


def _edges(sg: SurfaceGraph, faces: npt.NDArray[np.int64]) -> list[tuple[int, int, int, int]]:
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


def _fold_flat(faces: npt.NDArray[np.int64], folds: list[tuple[int, int, int, int]], f: int):  # noqa: ANN202
    """Cells, rotations, parents (from ``faces[0]``) and the fold into each face of the tree ``folds``."""
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


def _tree_path(u: int, v: int, parent: npt.NDArray[np.int64], via: npt.NDArray[np.int64]) -> list[int]:
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


def _short_overlaps(sg: SurfaceGraph, faces: npt.NDArray[np.int64], edges: list[tuple[int, int, int, int]],
                    longest: int, deadline: float) -> list[tuple[int, ...]]:
    """Every path of at most ``longest`` folds whose two end faces fold onto one cell (indices in ``edges``).

    Only the shortest such paths are kept (a path holding one is not extended),
    each once whichever end it starts from.
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


def _slits(sg: SurfaceGraph, edges: list[tuple[int, int, int, int]], cut: list, solver,  # noqa: ANN001
           cell: npt.NDArray[np.int64], rot: npt.NDArray[np.int64]) -> list[tuple[int, int]]:
    """The two faces of each cut edge inside the path whose sides meet in the plane anyway.

    Such an edge closes up (the net keeps it as a fold), which splits the cut
    path in two: not a zipper.  At an end of the path it only shortens the path.
    """
    ends: dict[int, int] = {}
    cuts = []
    for (a, k, b, kb), (uv, vu) in zip(edges, cut):
        if solver.BooleanValue(uv) or solver.BooleanValue(vu):
            cuts.append((a, k, b, kb))
            for v in (int(sg.vertex[a, k]), int(sg.vertex[a, (k + 1) % 4])):
                ends[v] = ends.get(v, 0) + 1
    out = []
    for a, k, b, kb in cuts:
        if ends[int(sg.vertex[a, k])] == 1 or ends[int(sg.vertex[a, (k + 1) % 4])] == 1:
            continue
        s = (k + int(rot[a])) % 4
        if (tuple(cell[b]) == (int(cell[a, 0]) + _SIDE_STEP[s][0], int(cell[a, 1]) + _SIDE_STEP[s][1])
                and int(rot[b]) == (s + 2 - kb) % 4):
            out.append((a, b))
    return out


def zipper_layout(sg: SurfaceGraph, faces: npt.NDArray[np.int64], deadline: float) -> ExactLayout:
    """A zipper net of the surface part ``faces`` in any box, or a proof that none exists.

    Parameters
    ----------
    sg : SurfaceGraph
    faces : (P,) int ndarray
        The faces of one connected surface part, increasing.
    deadline : float
        ``time.monotonic()`` at which the search gives up.

    Returns
    -------
    ExactLayout
        Cells (from 0), rotations and fold-tree parents; ``box`` is the net's extent.

    Raises
    ------
    NoNetExistsError
        No zipper net exists (proved), ``why`` says how.
    Undecided
        The deadline came first.
    """
    f = sg.face_count
    n = int(faces.size)
    edges = _edges(sg, faces)
    corner = sg.vertex[faces]
    verts = np.unique(corner)
    index = {int(v): i for i, v in enumerate(verts.tolist())}
    genus2 = 2 - (verts.size - len(edges) + n)  # twice the genus, by Euler
    if genus2 < 0:
        raise UnfoldError(f"the {n}-face surface is not one closed surface (Euler characteristic {2 - genus2})")
    if genus2 > 0:
        raise NoNetExistsError(None, None, kind="zipper net", why=(
            f"the {n}-face surface has a handle (Euler characteristic {2 - genus2}), so the cut edges of any "
            "of its nets hold a cycle, never one path"))
    # Vertices of the voxel lattice take two colours (x + y + z even or odd) and every edge joins
    # two colours, so a path through all of them has as many of each, give or take one.
    colour = sg.vertex_position[verts].sum(axis=1) % 2
    even, odd = int((colour == 0).sum()), int((colour == 1).sum())
    if abs(even - odd) > 1:
        raise NoNetExistsError(None, None, kind="zipper net", why=(
            f"the {n}-face surface has {even} vertices of one colour and {odd} of the other (x + y + z even "
            "or odd), and a cut path alternates colours"))
    cp_model = _cp_model()
    m = cp_model.CpModel()
    dummy = int(verts.size)
    arcs = []
    cut = []
    for i, (a, k, _, _) in enumerate(edges):
        u, v = index[int(sg.vertex[a, k])], index[int(sg.vertex[a, (k + 1) % 4])]
        uv, vu = m.NewBoolVar(f"u{i}"), m.NewBoolVar(f"v{i}")
        arcs += [(u, v, uv), (v, u, vu)]
        cut.append((uv, vu))
    for v in range(dummy):  # the path's two ends, joined through the dummy node into one circuit
        arcs += [(dummy, v, m.NewBoolVar(f"s{v}")), (v, dummy, m.NewBoolVar(f"t{v}"))]
    m.AddCircuit(arcs)
    # A path and its reverse are one cut: the end at the lower vertex is the start.
    starts = [lit for (t, _, lit) in arcs if t == dummy]
    ends = [lit for (_, h, lit) in arcs if h == dummy]
    for v in range(dummy):
        m.Add(sum(ends[: v + 1]) >= 1).OnlyEnforceIf(starts[v])
    for path in _short_overlaps(sg, faces, edges, _SHORT_PATH, deadline):
        m.AddBoolOr([lit for i in path for lit in cut[i]])
    solver = one_worker_solver()
    prm = solver.parameters
    # The model is solved again after each round of no-goods: presolving it each time costs more
    # than it saves, and it drops the previous path given as a hint (measured: 10 of 12 explored
    # shapes decided in 8 s without presolve, 3 with it).
    prm.cp_model_presolve = False
    rounds = 0
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            break
        prm.max_time_in_seconds = left
        status = _solve(solver, m)
        if status == cp_model.INFEASIBLE:
            raise NoNetExistsError(None, None, kind="zipper net", why=(
                f"every path through the {dummy} vertices of the {n}-face surface folds into an overlap "
                f"({rounds} overlaps ruled out)"))
        if status not in (cp_model.OPTIMAL, cp_model.FEASIBLE):
            break
        folds = [e for e, (uv, vu) in zip(edges, cut)
                 if not (solver.BooleanValue(uv) or solver.BooleanValue(vu))]
        fold_cut = [cut[i] for i, (uv, vu) in enumerate(cut)
                    if not (solver.BooleanValue(uv) or solver.BooleanValue(vu))]
        cell, rot, parent, via = _fold_flat(faces, folds, f)
        owner: dict[tuple[int, int], int] = {}
        clashes = []
        for a in faces.tolist():
            c = (int(cell[a, 0]), int(cell[a, 1]))
            if c in owner:
                clashes.append((owner[c], a))
            else:
                owner[c] = a
        if not clashes:
            clashes = _slits(sg, edges, cut, solver, cell, rot)
        if not clashes:
            xy = cell[faces]
            lo = xy.min(axis=0)
            out = cell - lo
            w, h = (xy.max(axis=0) - lo + 1).tolist()
            return ExactLayout(out, rot, parent, (int(w), int(h)))
        for u, v in clashes:
            # Every tree holding these folds lays u and v on one cell (or side by side across their
            # cut edge): one of them must be cut.
            m.AddBoolOr([lit for i in _tree_path(u, v, parent, via) for lit in fold_cut[i]])
        rounds += 1
        # Start the next search from this path: most of it is far from the overlaps.
        m.ClearHints()
        for uv, vu in cut:
            m.AddHint(uv, solver.BooleanValue(uv))
            m.AddHint(vu, solver.BooleanValue(vu))
    raise Undecided(
        f"undecided: the zipper search ran out of time before it found a zipper net of the {n}-face "
        f"surface or proved that none exists ({rounds} overlaps ruled out); raise the timeout")
